// The declarations of a config: every key once, with its unit, type, default, bound and
// meaning, bound to the typed member it fills (in the manner of deal.II's declare_entry).
// Reading, located errors, dotted paths, the resolved config, its hash and the key reference
// of docs/config.md all walk these tables; config/builder.hpp declares them.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/bound.hpp"
#include "config/value.hpp"
#include "core/violation.hpp"

namespace sb::config {

enum class Type {
    number,           ///< a float (an integer is accepted)
    integer,          ///< a whole number
    boolean,          ///< true or false
    string,           ///< free text or a name
    choice,           ///< one of a fixed list of names (an enum)
    vector3,          ///< 3 numbers
    numbers,          ///< an array of numbers
    strings,          ///< an array of strings
    file,             ///< a file name, relative to the config's folder
    table,            ///< [key]
    named_tables,     ///< [key.NAME], one table per name
    array_of_tables,  ///< [[key]]
    named_numbers,    ///< [key] with NAME = number lines
};

/// What an absent key means.
enum class Presence {
    defaulted,  ///< the typed member keeps its default
    required,   ///< it must be given
    automatic,  ///< the bench chooses it; also written "automatic" (a std::optional member)
    optional,   ///< it is not used (a std::optional member, or an empty name)
    follows,    ///< the value of another key of the same table, resolved when it is used
};

/// Everything a user, a message, the docs and calibration know of one key.
struct Declaration {
    std::string key;  ///< relative to its table, units in the name: "length_m"
    Type type = Type::number;
    Presence presence = Presence::defaulted;
    Value default_value;    ///< defaulted: the typed member's default
    std::string follows;    ///< follows: the key of the same table whose value it takes
    std::string automatic;  ///< automatic: how the bench chooses the value
    Bound bound;            ///< numbers, integers, and every element of arrays and vectors
    std::vector<std::string> choices;  ///< choice: the names, in declaration order
    std::string unit;                  ///< "m", "Pa", "g", "-" ...; empty for names and flags
    std::string meaning;               ///< short, for messages: "beam length"
    std::string doc;                   ///< longer text for docs/config.md; empty: meaning
    /// The key under which the leaf module's validate() reports this member, relative to the
    /// leaf key of the table (empty: the same as key). Lets a leaf's violation be reported at
    /// the key the user wrote, with the meaning declared here.
    std::string leaf;
    /// When the key does not apply (see Entry::active): why, for messages and docs.
    std::string inactive_reason;
    /// A key that does not apply but is given is an error (otherwise it is ignored).
    bool reject_inactive = false;
    /// The default search interval of `shakerbench calibrate` when this key is freed without
    /// one: the physically plausible values, narrower than `bound` (which only says what can
    /// run). Absent: a freed key needs its interval on the command line.
    std::optional<std::array<double, 2>> calibration_range;
    /// Whole numbers this integer member can hold.
    double integer_lo = -1e9;
    double integer_hi = 1e9;

    /// "beam length [m]": the meaning with the unit, as messages give it.
    [[nodiscard]] std::string meaning_with_unit() const;
    /// "number > 0 [m]", "integer >= 2", "\"up\", \"down\"", "3 numbers [m]": for docs.
    [[nodiscard]] std::string type_text() const;
    /// "0.05", "required", "automatic", "as `sliding_friction`", "absent": for docs.
    [[nodiscard]] std::string default_text() const;
    [[nodiscard]] const std::string& leaf_key() const { return leaf.empty() ? key : leaf; }
    [[nodiscard]] bool is_value() const { return type < Type::table; }
};

class Table;

/// One declared key bound to its typed member. The functions act on the object that the
/// table holding the entry fills, passed as void* (config/builder.hpp knows its type).
struct Entry {
    Declaration decl;
    /// Null: the key always applies; else whether it applies to this object (a beam's keys
    /// only to a structure of kind "beam").
    std::function<bool(const void*)> active;

    // Values. get gives the stored value: std::monostate for an automatic or absent one, and
    // for a `follows` key that was not given (effective_value() resolves it).
    std::function<Value(const void*)> get;
    std::function<void(void*, const Value&)> set;  ///< a value accept() has passed

    // Tables and collections.
    std::shared_ptr<const Table> table;  ///< the sub-table's, or each element's, declarations
    std::function<void*(void*)> sub;     ///< table: the object it fills (may be the same)
    std::function<std::size_t(const void*)> size;
    std::function<void*(void*, std::size_t)> element;
    std::function<std::string(const void*, std::size_t)> element_name;
    /// A new element at the end (named: with this name); returns it.
    std::function<void*(void*, const std::string&)> append;
    // named_numbers: each element's value, declared by element_decl.
    std::function<Value(const void*, std::size_t)> element_get;
    std::function<void(void*, std::size_t, const Value&)> element_set;
    Declaration element_decl;

    [[nodiscard]] bool applies(const void* object) const { return !active || active(object); }
    [[nodiscard]] const void* sub_of(const void* object) const {
        return sub(const_cast<void*>(object));
    }
    [[nodiscard]] const void* element_of(const void* object, std::size_t i) const {
        return element(const_cast<void*>(object), i);
    }
};

/// A check across keys (a leaf module's validate(), points that must exist): violations keyed
/// by leaf keys relative to the table's object. It runs only when no error was reported
/// within its table (and the further paths in `needs`, relative to the root), so that it
/// never judges values that could not be read.
struct Check {
    std::function<Violations(const void*)> run;
    std::vector<std::string> needs;
};

/// The declarations of one table, in the order they are documented and written.
class Table {
  public:
    std::string title;  ///< heading in docs/config.md: "the contact law"
    std::string doc;    ///< paragraph for docs/config.md
    std::vector<Entry> entries;
    std::vector<Check> checks;

    [[nodiscard]] const Entry* find(std::string_view key) const;
};

/// Whether `value` may be given for `decl` and in what form it is kept: an integer where a
/// number is declared becomes a double, "automatic" becomes std::monostate, a choice is
/// checked against its names and every number against the bound. On a problem returns its
/// constraint ("must be > 0"), and `element` the offending array element (else -1).
struct Problem {
    std::string constraint;
    int element = -1;
};
std::optional<Problem> accept(const Declaration& decl, Value& value);

/// The value a key has for the bench: the stored one, or for a `follows` key that was not
/// given the value of the key it follows.
Value effective_value(const Table& table, const Entry& entry, const void* object);

/// A leaf key (as a leaf module's validate() reports it, relative to the table) turned into
/// the config key relative to the table, with the declaration it names; nothing when no
/// declared key matches.
struct MappedKey {
    std::string key;
    const Declaration* decl = nullptr;
};
std::optional<MappedKey> map_leaf_key(const Table& table, std::string_view leaf_key);

/// Path text: "a.b", "a[2].x", quoting names that are not bare TOML keys.
std::string join_path(std::string_view prefix, std::string_view key);
std::string index_path(std::string_view prefix, std::size_t index);
/// A name as a TOML key: bare when it can be, else quoted.
std::string key_text(std::string_view name);

}  // namespace sb::config

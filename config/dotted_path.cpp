// Getting and setting config values by dotted path.
#include "config/dotted_path.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "config/read.hpp"

namespace sb::config {
namespace {

/// The value a path names: its entry, the object holding it and, for NAME = number tables,
/// the element.
struct Target {
    const Table* table = nullptr;
    const Entry* entry = nullptr;
    void* object = nullptr;
    bool is_element = false;
    std::size_t index = 0;
    /// One number of a vector or array key ("...rotational_stiffness_nm_per_rad[1]"): its
    /// index and its declaration (the key's unit, bound and calibration interval).
    std::optional<std::size_t> component;
    const Declaration* component_decl = nullptr;
    std::string path;       ///< canonical text of the path
    std::string value_key;  ///< the path of the key holding the value (without a component)
};

ConfigError located_error(std::string_view path, std::string constraint, std::string meaning,
                          const Origin& origin) {
    ConfigError e;
    e.file = origin.file;
    e.line = origin.line;
    e.column = origin.column;
    e.key_path = std::string(path);
    e.constraint = std::move(constraint);
    e.meaning = std::move(meaning);
    return e;
}

[[noreturn]] void fail(std::string_view path, std::string constraint, std::string meaning,
                       const Origin& origin) {
    throw ConfigException({located_error(path, std::move(constraint), std::move(meaning), origin)});
}

const char* kSeeKeys = "see docs/config.md or `shakerbench keys CONFIG` for the keys";

/// A key that does not apply (yet): set_text_all() tries it again after the other
/// assignments, one of which may switch it on.
class NotApplicable : public ConfigException {
  public:
    using ConfigException::ConfigException;
};

/// The declaration of number `index` of a vector or array entry: the entry's unit, bound and
/// calibration interval, its default's number. Made once per entry and index and kept for the
/// program's life, as the tables' own declarations are (declaration() returns a reference).
const Declaration& component_declaration(const Entry& entry, std::size_t index) {
    static std::mutex mutex;
    static std::map<std::pair<const Entry*, std::size_t>, std::unique_ptr<const Declaration>> made;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& slot = made[{&entry, index}];
    if (!slot) {
        const Declaration& whole = entry.decl;
        auto d = std::make_unique<Declaration>(whole);
        d->key = index_path(whole.key, index);
        d->type = Type::number;
        const auto* defaults = std::get_if<std::vector<double>>(&whole.default_value);
        if (defaults != nullptr && index < defaults->size()) {
            d->presence = Presence::defaulted;
            d->default_value = (*defaults)[index];
        } else {
            d->presence = Presence::optional;
            d->default_value = std::monostate{};
        }
        d->meaning = whole.meaning + ", number " + std::to_string(index);
        slot = std::move(d);
    }
    return *slot;
}

/// `t` narrowed to the number at `index` of its vector or array key.
Target with_component(Target t, std::size_t index, const Origin& origin) {
    const Value value = effective_value(*t.table, *t.entry, t.object);
    const auto* numbers = std::get_if<std::vector<double>>(&value);
    const std::size_t size = numbers == nullptr ? 0 : numbers->size();
    t.path = index_path(t.path, index);
    if (index >= size) {
        fail(t.path, "the value has " + std::to_string(size) + " numbers", t.entry->decl.meaning,
             origin);
    }
    t.component = index;
    t.component_decl = &component_declaration(*t.entry, index);
    return t;
}

Target resolve(const Table& root, void* object, std::string_view path, const Origin& origin) {
    std::vector<PathPart> parts;
    if (!split_path(path, parts)) {
        fail(path, "is not a dotted key path (a.b.c, a.b[0].c)", kSeeKeys, origin);
    }
    Target t;
    t.table = &root;
    t.object = object;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const PathPart& part = parts[i];
        if (part.is_index) fail(path, "unknown key", kSeeKeys, origin);
        const Entry* e = t.table->find(part.name);
        if (e == nullptr) fail(path, "unknown key", kSeeKeys, origin);
        t.path = join_path(t.path, part.name);
        if (!e->applies(t.object)) {
            throw NotApplicable({located_error(t.path, "does not apply: " + e->decl.inactive_reason,
                                               e->decl.meaning, origin)});
        }
        const bool last = i + 1 == parts.size();
        switch (e->decl.type) {
            case Type::table:
                if (last) fail(path, "is a table, not a value", e->decl.meaning, origin);
                t.object = e->sub(t.object);
                t.table = e->table.get();
                break;
            case Type::named_tables:
            case Type::named_numbers: {
                if (last || parts[i + 1].is_index) {
                    fail(path, "names a table: add the name of one of its entries", e->decl.meaning,
                         origin);
                }
                const std::string& name = parts[++i].name;
                std::optional<std::size_t> found;
                for (std::size_t k = 0; k < e->size(t.object); ++k) {
                    if (e->element_name(t.object, k) == name) found = k;
                }
                t.path = join_path(t.path, name);
                if (!found) {
                    fail(t.path, "the config has no such entry", e->decl.meaning, origin);
                }
                if (e->decl.type == Type::named_numbers) {
                    if (i + 1 != parts.size()) fail(path, "unknown key", kSeeKeys, origin);
                    t.entry = e;
                    t.is_element = true;
                    t.index = *found;
                    t.value_key = t.path;
                    return t;
                }
                t.object = e->element(t.object, *found);
                t.table = e->table.get();
                if (i + 1 == parts.size()) {
                    fail(path, "is a table, not a value", e->decl.meaning, origin);
                }
                break;
            }
            case Type::array_of_tables: {
                if (last || !parts[i + 1].is_index) {
                    fail(path, "names an array of tables: add an index, [0] for the first",
                         e->decl.meaning, origin);
                }
                const std::size_t index = parts[++i].index;
                t.path = index_path(t.path, index);
                if (index >= e->size(t.object)) {
                    fail(t.path,
                         "the config has " + std::to_string(e->size(t.object)) + " such entries",
                         e->decl.meaning, origin);
                }
                t.object = e->element(t.object, index);
                t.table = e->table.get();
                if (i + 1 == parts.size()) {
                    fail(path, "is a table, not a value", e->decl.meaning, origin);
                }
                break;
            }
            case Type::vector3:
            case Type::numbers:
                t.entry = e;
                t.value_key = t.path;
                if (last) return t;
                if (!parts[i + 1].is_index || i + 2 != parts.size()) {
                    fail(path, "unknown key", kSeeKeys, origin);
                }
                return with_component(t, parts[i + 1].index, origin);
            default:
                if (!last) fail(path, "unknown key", kSeeKeys, origin);
                t.entry = e;
                t.value_key = t.path;
                return t;
        }
    }
    fail(path, "unknown key", kSeeKeys, origin);
}

const Declaration& decl_of(const Target& t) {
    if (t.component_decl) return *t.component_decl;
    return t.is_element ? t.entry->element_decl : t.entry->decl;
}

/// The number `index` of a vector or array value.
Value number_at(const Value& whole, std::size_t index) {
    return std::get<std::vector<double>>(whole).at(index);
}

Value current(const Target& t) {
    if (t.component) return number_at(effective_value(*t.table, *t.entry, t.object), *t.component);
    return t.is_element ? t.entry->element_get(t.object, t.index)
                        : effective_value(*t.table, *t.entry, t.object);
}

Value stored(const Target& t) {
    if (t.component) return number_at(effective_value(*t.table, *t.entry, t.object), *t.component);
    return t.is_element ? t.entry->element_get(t.object, t.index) : t.entry->get(t.object);
}

void assign(const Target& t, const Value& v) {
    if (t.component) {
        // The whole vector as the bench holds it, with one number changed.
        auto whole = std::get<std::vector<double>>(effective_value(*t.table, *t.entry, t.object));
        double number = 0.0;
        as_number(v, number);
        whole.at(*t.component) = number;
        t.entry->set(t.object, whole);
    } else if (t.is_element) {
        t.entry->element_set(t.object, t.index, v);
    } else {
        t.entry->set(t.object, v);
    }
}

/// Applies a checked value, runs the checks, and undoes it when they fail.
void apply(const Table& root, void* object, SourceMap& where, const Target& t, const Value& v,
           const Origin& origin) {
    const Value before = stored(t);
    assign(t, v);
    where.overrides.emplace_back(t.value_key, origin);
    Diagnostics diagnostics;
    check(root, object, where, diagnostics);
    if (!diagnostics.empty()) {
        assign(t, before);
        where.overrides.pop_back();
        diagnostics.throw_if_any();
    }
}

}  // namespace

Value get(const Table& root, const void* object, std::string_view path) {
    return current(resolve(root, const_cast<void*>(object), path, {"<get>", 0, 0}));
}

const Declaration& declaration(const Table& root, const void* object, std::string_view path) {
    return decl_of(resolve(root, const_cast<void*>(object), path, {"<get>", 0, 0}));
}

void set(const Table& root, void* object, SourceMap& where, std::string_view path, Value value,
         const Origin& origin) {
    const Target t = resolve(root, object, path, origin);
    const Declaration& d = decl_of(t);
    const std::string text = value_text(value);
    if (auto problem = accept(d, value)) {
        Diagnostics diagnostics;
        diagnostics.add(origin, t.path, text, problem->constraint, d.meaning_with_unit());
        diagnostics.throw_if_any();
    }
    apply(root, object, where, t, value, origin);
}

void set_text(const Table& root, void* object, SourceMap& where, std::string_view path,
              std::string_view text, const Origin& origin) {
    const Target t = resolve(root, object, path, origin);
    Diagnostics diagnostics;
    Value value;
    if (!value_from_text(decl_of(t), text, t.path, origin, diagnostics, value)) {
        diagnostics.throw_if_any();
    }
    apply(root, object, where, t, value, origin);
}

void set_text_all(const Table& root, void* object, SourceMap& where,
                  const std::vector<TextAssignment>& assignments, const Origin& origin) {
    struct Undo {
        Target target;
        Value before;
    };
    std::vector<Undo> undo;
    const std::size_t overrides_before = where.overrides.size();
    const auto undo_all = [&] {
        for (auto it = undo.rbegin(); it != undo.rend(); ++it) assign(it->target, it->before);
        where.overrides.resize(overrides_before);
    };
    Diagnostics diagnostics;
    // In order; an assignment to a key that does not apply waits for the others (one of them
    // may switch it on: a joint's exponent before its stiffness) and is tried again while
    // that makes progress, so the order of the assignments does not matter.
    std::vector<const TextAssignment*> pending;
    for (const auto& a : assignments) pending.push_back(&a);
    std::vector<ConfigError> not_applicable;
    for (bool progress = true; progress && !pending.empty();) {
        progress = false;
        not_applicable.clear();
        std::vector<const TextAssignment*> waiting;
        for (const TextAssignment* a : pending) {
            try {
                // Resolved after the earlier assignments, so a path may depend on them.
                const Target t = resolve(root, object, a->path, origin);
                progress = true;
                Value value;
                if (!value_from_text(decl_of(t), a->text, t.path, origin, diagnostics, value)) {
                    continue;
                }
                undo.push_back({t, stored(t)});
                assign(t, value);
                where.overrides.emplace_back(t.value_key, origin);
            } catch (const NotApplicable& e) {
                waiting.push_back(a);
                for (const auto& error : e.errors()) not_applicable.push_back(error);
            } catch (const ConfigException& e) {
                progress = true;
                for (const auto& error : e.errors()) diagnostics.add(error);
            }
        }
        pending = std::move(waiting);
    }
    for (const auto& error : not_applicable) diagnostics.add(error);
    if (diagnostics.empty()) check(root, object, where, diagnostics);
    if (!diagnostics.empty()) {
        undo_all();
        diagnostics.throw_if_any();
    }
}

bool split_assignment(std::string_view assignment, std::string& key, std::string& value) {
    const auto eq = assignment.find('=');
    if (eq == std::string_view::npos || eq == 0) return false;
    key = std::string(assignment.substr(0, eq));
    value = std::string(assignment.substr(eq + 1));
    while (!key.empty() && key.back() == ' ') key.pop_back();
    while (!value.empty() && value.front() == ' ') value.erase(value.begin());
    return true;
}

}  // namespace sb::config

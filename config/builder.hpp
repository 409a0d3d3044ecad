// Declaring the keys of a table bound to the members of a typed struct T: one call per key,
// with its meaning, then its unit, bound and presence:
//
//     TableBuilder<BeamSpec> beam("the beam");
//     beam.number("length_m", [](BeamSpec& b) -> auto& { return b.length_m; }, "beam length")
//         .unit("m").bound(Bound::positive()).required();
//
// The default of a key is the member's value in a default-constructed T.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "config/schema.hpp"

namespace sb::config {

namespace detail {
template <class M>
struct IsOptional : std::false_type {};
template <class M>
struct IsOptional<std::optional<M>> : std::true_type {};
}  // namespace detail

template <class T>
class TableBuilder {
  public:
    explicit TableBuilder(std::string title, std::string doc = {})
        : table_(std::make_shared<Table>()) {
        table_->title = std::move(title);
        table_->doc = std::move(doc);
    }

    /// Further attributes of the key just declared.
    class Ref {
      public:
        Ref(TableBuilder* builder, std::size_t index) : builder_(builder), index_(index) {}
        Ref& unit(std::string u) {
            decl().unit = std::move(u);
            return *this;
        }
        Ref& bound(Bound b) {
            decl().bound = b;
            return *this;
        }
        /// The interval calibration searches when this key is freed without one.
        Ref& calibrated_within(double lo, double hi) {
            decl().calibration_range = std::array<double, 2>{lo, hi};
            return *this;
        }
        Ref& required() {
            decl().presence = Presence::required;
            return *this;
        }
        /// The bench chooses the value when it is absent or "automatic" (a std::optional member).
        Ref& automatic(std::string how) {
            decl().presence = Presence::automatic;
            decl().automatic = std::move(how);
            return *this;
        }
        /// Absent means not used (a std::optional member, or an empty name).
        Ref& optional() {
            decl().presence = Presence::optional;
            return *this;
        }
        /// Absent: the value of `key` of the same table, resolved when used (std::optional member).
        Ref& follows(std::string key) {
            decl().presence = Presence::follows;
            decl().follows = std::move(key);
            return *this;
        }
        /// The member's key in the leaf module's validate(), relative to the table's leaf key.
        Ref& leaf(std::string key) {
            decl().leaf = std::move(key);
            return *this;
        }
        /// The meaning messages give (for a table, its title by default).
        Ref& meaning(std::string text) {
            decl().meaning = std::move(text);
            return *this;
        }
        Ref& doc(std::string text) {
            decl().doc = std::move(text);
            return *this;
        }
        /// The key applies only when `applies` holds for the table's object; given otherwise it
        /// is ignored, or an error when `reject` is set.
        template <class Pred>
        Ref& when(Pred applies, std::string reason, bool reject = false) {
            entry().active = [applies](const void* o) { return applies(object(o)); };
            decl().inactive_reason = std::move(reason);
            decl().reject_inactive = reject;
            return *this;
        }

      private:
        Entry& entry() { return builder_->table_->entries[index_]; }
        Declaration& decl() { return entry().decl; }
        TableBuilder* builder_;
        std::size_t index_;
    };

    template <class Access>
    Ref number(std::string key, Access access, std::string meaning) {
        using M = Member<Access>;
        Entry e = make(std::move(key), Type::number, std::move(meaning));
        e.get = [access](const void* o) -> Value {
            auto& m = access(object(o));
            if constexpr (detail::IsOptional<M>::value) {
                return m ? Value(static_cast<double>(*m)) : Value(std::monostate{});
            } else {
                return Value(static_cast<double>(m));
            }
        };
        e.set = [access](void* o, const Value& v) {
            auto& m = access(object(o));
            if constexpr (detail::IsOptional<M>::value) {
                if (std::holds_alternative<std::monostate>(v)) {
                    m.reset();
                } else {
                    m = std::get<double>(v);
                }
            } else {
                m = std::get<double>(v);
            }
        };
        if constexpr (detail::IsOptional<M>::value) e.decl.presence = Presence::optional;
        return add(std::move(e));
    }

    template <class Access>
    Ref integer(std::string key, Access access, std::string meaning) {
        using M = Member<Access>;
        static_assert(std::is_integral_v<M>, "integer keys bind whole-number members");
        Entry e = make(std::move(key), Type::integer, std::move(meaning));
        constexpr double kReasonable = 1e9;  // far beyond any count, step or seed a config needs
        e.decl.integer_lo =
            std::max(static_cast<double>(std::numeric_limits<M>::lowest()), -kReasonable);
        if constexpr (std::is_unsigned_v<M>) e.decl.bound = Bound::non_negative();
        e.decl.integer_hi =
            std::min(static_cast<double>(std::numeric_limits<M>::max()), kReasonable);
        e.get = [access](const void* o) -> Value {
            return Value(static_cast<std::int64_t>(access(object(o))));
        };
        e.set = [access](void* o, const Value& v) {
            access(object(o)) = static_cast<M>(std::get<std::int64_t>(v));
        };
        return add(std::move(e));
    }

    template <class Access>
    Ref boolean(std::string key, Access access, std::string meaning) {
        Entry e = make(std::move(key), Type::boolean, std::move(meaning));
        e.get = [access](const void* o) -> Value { return Value(bool(access(object(o)))); };
        e.set = [access](void* o, const Value& v) { access(object(o)) = std::get<bool>(v); };
        return add(std::move(e));
    }

    /// A name or free text; with optional(), an empty string is absent.
    template <class Access>
    Ref string(std::string key, Access access, std::string meaning) {
        Entry e = make(std::move(key), Type::string, std::move(meaning));
        e.get = [access](const void* o) -> Value { return Value(access(object(o))); };
        e.set = [access](void* o, const Value& v) {
            access(object(o)) = std::holds_alternative<std::monostate>(v)
                                    ? std::string()
                                    : std::get<std::string>(v);
        };
        return add(std::move(e));
    }

    /// An enum member; `names` is its one name table: pairs of (enumerator, name).
    template <class Access, class Names>
    Ref choice(std::string key, Access access, const Names& names, std::string meaning) {
        using E = Member<Access>;
        std::vector<std::pair<E, std::string>> table;
        for (const auto& [value, name] : names) table.emplace_back(value, std::string(name));
        Entry e = make(std::move(key), Type::choice, std::move(meaning));
        for (const auto& [value, name] : table) e.decl.choices.push_back(name);
        e.get = [access, table](const void* o) -> Value {
            const E current = access(object(o));
            for (const auto& [value, name] : table) {
                if (value == current) return Value(name);
            }
            return Value(std::string("?"));
        };
        e.set = [access, table](void* o, const Value& v) {
            const auto& text = std::get<std::string>(v);
            for (const auto& [value, name] : table) {
                if (name == text) access(object(o)) = value;
            }
        };
        return add(std::move(e));
    }

    /// Three numbers into any member with operator[] (Eigen::Vector3d), or a std::optional of
    /// one (absent: not given).
    template <class Access>
    Ref vector3(std::string key, Access access, std::string meaning) {
        using M = Member<Access>;
        Entry e = make(std::move(key), Type::vector3, std::move(meaning));
        e.get = [access](const void* o) -> Value {
            const auto& m = access(object(o));
            if constexpr (detail::IsOptional<M>::value) {
                if (!m) return Value(std::monostate{});
                return Value(std::vector<double>{(*m)[0], (*m)[1], (*m)[2]});
            } else {
                return Value(std::vector<double>{m[0], m[1], m[2]});
            }
        };
        e.set = [access](void* o, const Value& v) {
            auto& m = access(object(o));
            if constexpr (detail::IsOptional<M>::value) {
                if (std::holds_alternative<std::monostate>(v)) {
                    m.reset();
                    return;
                }
                m.emplace();
                const auto& values = std::get<std::vector<double>>(v);
                for (int k = 0; k < 3; ++k) (*m)[k] = values[static_cast<std::size_t>(k)];
            } else {
                const auto& values = std::get<std::vector<double>>(v);
                for (int k = 0; k < 3; ++k) m[k] = values[static_cast<std::size_t>(k)];
            }
        };
        if constexpr (detail::IsOptional<M>::value) e.decl.presence = Presence::optional;
        return add(std::move(e));
    }

    template <class Access>
    Ref numbers(std::string key, Access access, std::string meaning) {
        Entry e = make(std::move(key), Type::numbers, std::move(meaning));
        e.get = [access](const void* o) -> Value { return Value(access(object(o))); };
        e.set = [access](void* o, const Value& v) {
            access(object(o)) = std::get<std::vector<double>>(v);
        };
        return add(std::move(e));
    }

    template <class Access>
    Ref strings(std::string key, Access access, std::string meaning) {
        Entry e = make(std::move(key), Type::strings, std::move(meaning));
        e.get = [access](const void* o) -> Value { return Value(access(object(o))); };
        e.set = [access](void* o, const Value& v) {
            access(object(o)) = std::get<std::vector<std::string>>(v);
        };
        return add(std::move(e));
    }

    /// A std::filesystem::path member; the reader resolves it against the config's folder.
    template <class Access>
    Ref file(std::string key, Access access, std::string meaning) {
        Entry e = make(std::move(key), Type::file, std::move(meaning));
        e.get = [access](const void* o) -> Value { return Value(access(object(o)).string()); };
        e.set = [access](void* o, const Value& v) {
            access(object(o)) = std::holds_alternative<std::monostate>(v)
                                    ? std::filesystem::path()
                                    : std::filesystem::path(std::get<std::string>(v));
        };
        return add(std::move(e));
    }

    /// [key]: a sub-table filling the member `access` returns (which may be the object itself).
    template <class Access>
    Ref table(std::string key, Access access, std::shared_ptr<const Table> schema) {
        Entry e = make(std::move(key), Type::table, schema->title);
        e.table = std::move(schema);
        e.sub = [access](void* o) -> void* { return &access(object(o)); };
        return add(std::move(e));
    }

    /// [key.NAME]: one element of the vector `access` returns per name; `name` gives its name.
    template <class Access, class Name>
    Ref named_tables(std::string key, Access access, Name name,
                     std::shared_ptr<const Table> schema) {
        using U = typename Member<Access>::value_type;
        Entry e = make(std::move(key), Type::named_tables, schema->title);
        e.table = std::move(schema);
        collection(e, access);
        e.element_name = [access, name](const void* o, std::size_t i) -> std::string {
            return name(access(object(o))[i]);
        };
        e.append = [access, name](void* o, const std::string& n) -> void* {
            auto& v = access(object(o));
            v.push_back(U{});
            name(v.back()) = n;
            return &v.back();
        };
        return add(std::move(e));
    }

    /// [[key]]: the elements of the vector `access` returns, in file order.
    template <class Access>
    Ref array_of_tables(std::string key, Access access, std::shared_ptr<const Table> schema) {
        using U = typename Member<Access>::value_type;
        Entry e = make(std::move(key), Type::array_of_tables, schema->title);
        e.table = std::move(schema);
        collection(e, access);
        e.append = [access](void* o, const std::string&) -> void* {
            auto& v = access(object(o));
            v.push_back(U{});
            return &v.back();
        };
        return add(std::move(e));
    }

    /// [key] of NAME = number lines: elements of the vector `access` returns, named by `name`,
    /// their number in the member `value` gives, each declared by `element` (type number or
    /// integer, unit, bound, meaning).
    template <class Access, class Name, class ValueOf>
    Ref named_numbers(std::string key, Access access, Name name, ValueOf value, Declaration element,
                      std::string meaning) {
        using U = typename Member<Access>::value_type;
        Entry e = make(std::move(key), Type::named_numbers, std::move(meaning));
        e.element_decl = std::move(element);
        e.element_decl.presence = Presence::required;  // every NAME = line gives its number
        collection(e, access);
        e.element_name = [access, name](const void* o, std::size_t i) -> std::string {
            return name(access(object(o))[i]);
        };
        e.append = [access, name](void* o, const std::string& n) -> void* {
            auto& v = access(object(o));
            v.push_back(U{});
            name(v.back()) = n;
            return &v.back();
        };
        e.element_get = [access, value](const void* o, std::size_t i) -> Value {
            auto& m = value(access(object(o))[i]);
            if constexpr (std::is_integral_v<std::remove_cvref_t<decltype(m)>>) {
                return Value(static_cast<std::int64_t>(m));
            } else {
                return Value(static_cast<double>(m));
            }
        };
        e.element_set = [access, value](void* o, std::size_t i, const Value& v) {
            auto& m = value(access(object(o))[i]);
            using V = std::remove_cvref_t<decltype(m)>;
            if constexpr (std::is_integral_v<V>) {
                m = static_cast<V>(std::get<std::int64_t>(v));
            } else {
                m = std::get<double>(v);
            }
        };
        return add(std::move(e));
    }

    /// A check across keys of this table: `run` returns leaf-keyed violations.
    template <class Run>
    void check(Run run, std::vector<std::string> needs = {}) {
        table_->checks.push_back(
            {[run](const void* o) -> Violations { return run(object(o)); }, std::move(needs)});
    }

    [[nodiscard]] std::shared_ptr<const Table> build() { return table_; }

  private:
    template <class Access>
    using Member = std::remove_cvref_t<std::invoke_result_t<Access, T&>>;

    static T& object(const void* o) { return *static_cast<T*>(const_cast<void*>(o)); }

    Entry make(std::string key, Type type, std::string meaning) {
        Entry e;
        e.decl.key = std::move(key);
        e.decl.type = type;
        e.decl.meaning = std::move(meaning);
        return e;
    }

    Ref add(Entry e) {
        if (e.get) e.decl.default_value = e.get(&prototype_);
        table_->entries.push_back(std::move(e));
        return Ref(this, table_->entries.size() - 1);
    }

    template <class Access>
    static void collection(Entry& e, Access access) {
        e.size = [access](const void* o) -> std::size_t { return access(object(o)).size(); };
        e.element = [access](void* o, std::size_t i) -> void* { return &access(object(o))[i]; };
    }

    std::shared_ptr<Table> table_;
    T prototype_{};
};

}  // namespace sb::config

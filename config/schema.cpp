// Declarations: their texts, the check of a given value, and leaf keys turned into config keys.
#include "config/schema.hpp"

#include <algorithm>
#include <cmath>

namespace sb::config {

std::string Declaration::meaning_with_unit() const {
    if (unit.empty()) return meaning;
    // The unit belongs to the first clause; what follows a "; " explains further.
    const auto clause = meaning.find("; ");
    if (clause == std::string::npos) return meaning + " [" + unit + "]";
    return meaning.substr(0, clause) + " [" + unit + "]" + meaning.substr(clause);
}

namespace {

std::string with_bound(const std::string& text, const Bound& bound) {
    const std::string b = bound.text();
    return b.empty() ? text : text + " " + b;
}

std::string with_unit(const std::string& text, const std::string& unit) {
    return unit.empty() ? text : text + " [" + unit + "]";
}

std::string choice_list(const std::vector<std::string>& choices) {
    std::string list;
    for (const auto& c : choices) {
        list += (list.empty() ? "" : ", ") + config::quoted(c);
    }
    return list;
}

}  // namespace

std::string Declaration::type_text() const {
    std::string text;
    switch (type) {
        case Type::number:
            text = with_unit(with_bound("number", bound), unit);
            break;
        case Type::integer:
            text = with_unit(with_bound("integer", bound), unit);
            break;
        case Type::boolean:
            text = "boolean";
            break;
        case Type::string:
            text = "string";
            break;
        case Type::choice:
            text = choice_list(choices);
            break;
        case Type::vector3:
            text = with_unit(with_bound("3 numbers", bound), unit);
            break;
        case Type::numbers:
            text = with_unit(with_bound("numbers", bound), unit);
            break;
        case Type::strings:
            text = "strings";
            break;
        case Type::file:
            text = "file name";
            break;
        case Type::table:
        case Type::named_tables:
        case Type::array_of_tables:
        case Type::named_numbers:
            text = "table";
            break;
    }
    if (presence == Presence::automatic) {
        text += " or " + config::quoted(kAutomatic);
    }
    return text;
}

std::string Declaration::default_text() const {
    switch (presence) {
        case Presence::required:
            return "required";
        case Presence::automatic:
            return std::string(kAutomatic);
        case Presence::optional:
            return "absent";
        case Presence::follows:
            return "as " + follows;
        case Presence::defaulted:
            break;
    }
    return value_text(default_value);
}

const Entry* Table::find(std::string_view key) const {
    for (const auto& e : entries) {
        if (e.decl.key == key) return &e;
    }
    return nullptr;
}

namespace {

std::optional<Problem> check_number(const Declaration& d, double v, int element) {
    if (!d.bound.contains(v)) {
        if (std::isinf(v) && !d.bound.infinite_allowed && d.bound.text().empty()) {
            return Problem{"must be finite", element};
        }
        const std::string c = d.bound.constraint();
        return Problem{element >= 0 ? "every value " + c : c, element};
    }
    return std::nullopt;
}

std::string type_constraint(const Declaration& d) {
    std::string c;
    switch (d.type) {
        case Type::number:
            c = "must be a number";
            break;
        case Type::integer:
            c = "must be an integer";
            break;
        case Type::boolean:
            c = "must be true or false";
            break;
        case Type::string:
        case Type::file:
            c = "must be a string";
            break;
        case Type::choice: {
            std::string list;
            for (const auto& name : d.choices) list += (list.empty() ? "" : ", ") + name;
            c = "must be one of: " + list;
            break;
        }
        case Type::vector3:
            c = "must be an array of 3 numbers";
            break;
        case Type::numbers:
            c = "must be an array of numbers";
            break;
        case Type::strings:
            c = "must be an array of strings";
            break;
        default:
            c = "must be a table";
            break;
    }
    if (d.presence == Presence::automatic) {
        c += " or " + config::quoted(kAutomatic);
    }
    return c;
}

}  // namespace

std::optional<Problem> accept(const Declaration& d, Value& value) {
    if (d.presence == Presence::automatic) {
        if (const auto* s = std::get_if<std::string>(&value); s != nullptr && *s == kAutomatic) {
            value = std::monostate{};
            return std::nullopt;
        }
    }
    const Problem wrong_type{type_constraint(d), -1};
    switch (d.type) {
        case Type::number: {
            double v = 0.0;
            if (!as_number(value, v)) return wrong_type;
            value = v;
            return check_number(d, v, -1);
        }
        case Type::integer: {
            const auto* i = std::get_if<std::int64_t>(&value);
            if (i == nullptr) return wrong_type;
            const auto v = static_cast<double>(*i);
            if (auto p = check_number(d, v, -1)) return p;
            if (v < d.integer_lo || v > d.integer_hi) {
                return Problem{"must be an integer of reasonable size", -1};
            }
            return std::nullopt;
        }
        case Type::boolean:
            if (!std::holds_alternative<bool>(value)) return wrong_type;
            return std::nullopt;
        case Type::string:
        case Type::file:
            if (!std::holds_alternative<std::string>(value)) return wrong_type;
            return std::nullopt;
        case Type::choice: {
            const auto* s = std::get_if<std::string>(&value);
            if (s == nullptr ||
                std::find(d.choices.begin(), d.choices.end(), *s) == d.choices.end()) {
                return wrong_type;
            }
            return std::nullopt;
        }
        case Type::vector3:
        case Type::numbers: {
            if (const auto* empty = std::get_if<std::vector<std::string>>(&value);
                empty != nullptr && empty->empty()) {
                value = std::vector<double>{};
            }
            const auto* v = std::get_if<std::vector<double>>(&value);
            if (v == nullptr || (d.type == Type::vector3 && v->size() != 3)) return wrong_type;
            for (std::size_t k = 0; k < v->size(); ++k) {
                if (auto p = check_number(d, (*v)[k], static_cast<int>(k))) return p;
            }
            return std::nullopt;
        }
        case Type::strings: {
            if (const auto* empty = std::get_if<std::vector<double>>(&value);
                empty != nullptr && empty->empty()) {
                value = std::vector<std::string>{};
            }
            if (!std::holds_alternative<std::vector<std::string>>(value)) return wrong_type;
            return std::nullopt;
        }
        default:
            return wrong_type;
    }
}

Value effective_value(const Table& table, const Entry& entry, const void* object) {
    Value v = entry.get(object);
    const auto* text = std::get_if<std::string>(&v);
    const bool absent =
        std::holds_alternative<std::monostate>(v) || (text != nullptr && text->empty());
    if (absent && entry.decl.presence == Presence::follows) {
        if (const Entry* followed = table.find(entry.decl.follows)) {
            return effective_value(table, *followed, object);
        }
    }
    return v;
}

namespace {

/// True when `key` is `prefix` or continues it with "." or "[".
bool continues(std::string_view key, std::string_view prefix) {
    if (key.substr(0, prefix.size()) != prefix) return false;
    return key.size() == prefix.size() || key[prefix.size()] == '.' || key[prefix.size()] == '[';
}

}  // namespace

std::optional<MappedKey> map_leaf_key(const Table& table, std::string_view leaf_key) {
    for (const auto& e : table.entries) {
        const std::string& leaf = e.decl.leaf_key();
        if (leaf.empty() || !continues(leaf_key, leaf)) continue;
        const std::string_view rest = leaf_key.substr(leaf.size());
        const std::string key = key_text(e.decl.key);
        switch (e.decl.type) {
            case Type::table:
                if (rest.empty()) return MappedKey{key, &e.decl};
                if (rest[0] == '.') {
                    if (auto inner = map_leaf_key(*e.table, rest.substr(1))) {
                        return MappedKey{join_path(key, "") + inner->key, inner->decl};
                    }
                }
                break;
            case Type::named_tables:
            case Type::named_numbers: {
                if (rest.empty()) return MappedKey{key, &e.decl};
                if (rest[0] != '.') break;
                const std::string_view after = rest.substr(1);
                if (e.decl.type == Type::named_numbers) {
                    // A number has no keys below it: the rest is its name, dots and all.
                    return MappedKey{join_path(key, after), &e.element_decl};
                }
                const auto dot = after.find('.');
                const std::string name(after.substr(0, dot));
                const std::string element = join_path(key, name);
                if (dot == std::string_view::npos) return MappedKey{element, &e.decl};
                if (auto inner = map_leaf_key(*e.table, after.substr(dot + 1))) {
                    return MappedKey{element + "." + inner->key, inner->decl};
                }
                break;
            }
            case Type::array_of_tables: {
                if (rest.empty()) return MappedKey{key, &e.decl};
                if (rest[0] != '[') break;
                const auto close = rest.find(']');
                if (close == std::string_view::npos) break;
                const std::string element = key + std::string(rest.substr(0, close + 1));
                const std::string_view after = rest.substr(close + 1);
                if (after.empty()) return MappedKey{element, &e.decl};
                if (after[0] != '.') break;
                if (auto inner = map_leaf_key(*e.table, after.substr(1))) {
                    return MappedKey{element + "." + inner->key, inner->decl};
                }
                break;
            }
            default:
                // A value, or one element of an array value ("offset_m[0]").
                if (rest.empty() || rest[0] == '[') {
                    return MappedKey{key + std::string(rest), &e.decl};
                }
                break;
        }
    }
    return std::nullopt;
}

std::string key_text(std::string_view name) {
    const bool bare = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    });
    return bare ? std::string(name) : config::quoted(name);
}

std::string join_path(std::string_view prefix, std::string_view key) {
    if (key.empty()) return std::string(prefix) + (prefix.empty() ? "" : ".");
    if (prefix.empty()) return key_text(key);
    return std::string(prefix) + "." + key_text(key);
}

std::string index_path(std::string_view prefix, std::size_t index) {
    return std::string(prefix) + "[" + std::to_string(index) + "]";
}

}  // namespace sb::config

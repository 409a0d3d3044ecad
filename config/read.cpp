// Reading a config document through its declarations, and running the checks across keys.
#include "config/read.hpp"

#include <cstdint>
#include <optional>
#include <set>
#include <sstream>

#include "config/toml_tree.hpp"

namespace sb::config {
namespace {

/// Text of a node as the file shows it, for messages.
std::string node_text(const toml::node& node) {
    if (node.is_table()) return "{...}";
    if (const auto* s = node.as_string()) return config::quoted(s->get());
    if (const auto* f = node.as_floating_point()) return number_text(f->get());
    std::ostringstream out;
    node.visit([&out](const auto& n) { out << n; });
    return out.str();
}

/// A bare word on the command line is written back into the resolved config as a TOML
/// string: it must be text a TOML file can hold (UTF-8), without control characters, which no
/// name or choice has and which would make the resolved config unreadable or ambiguous.
bool plain_word(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) return false;
        if (c < 0x80) {
            ++i;
            continue;
        }
        // The length of a UTF-8 sequence and the smallest code point it may encode (shorter
        // encodings of a code point, surrogates and values past U+10FFFF are not UTF-8).
        const std::size_t length = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc0 ? 2 : 0;
        if (length == 0 || c > 0xf4 || i + length > text.size()) return false;
        std::uint32_t code = c & (0x7fu >> length);
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(text[i + k]);
            if ((next & 0xc0) != 0x80) return false;
            code = (code << 6) | (next & 0x3fu);
        }
        const std::uint32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
        if (code < smallest || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) {
            return false;
        }
        // C1 control characters, like the C0 ones above.
        if (code >= 0x80 && code < 0xa0) return false;
        i += length;
    }
    return true;
}

std::string append_path(const std::string& prefix, const std::string& path_text) {
    return prefix.empty() ? path_text : prefix + "." + path_text;
}

class Reader {
  public:
    Reader(const Document& document, Diagnostics& diagnostics)
        : document_(document), diagnostics_(diagnostics) {}
    /// Every error placed at `origin` instead of in the document (a value from --set).
    void place_all_at(Origin origin) { forced_ = std::move(origin); }

    void table(const Table& schema, const toml::table* t, const Origin& where, void* object,
               const std::string& path) {
        std::set<std::string, std::less<>> used;
        for (const Entry& e : schema.entries) {
            used.insert(e.decl.key);
            const toml::node* node = t != nullptr ? t->get(e.decl.key) : nullptr;
            const std::string key_path = join_path(path, e.decl.key);
            if (!e.applies(object)) {
                if (node != nullptr && e.decl.reject_inactive) {
                    error(*node, key_path, node_text(*node),
                          "does not apply: " + e.decl.inactive_reason, e.decl.meaning);
                }
                continue;
            }
            if (node == nullptr) {
                if (e.decl.presence == Presence::required) {
                    diagnostics_.add(where, key_path, "", "is required",
                                     e.decl.meaning_with_unit());
                }
                continue;
            }
            entry(e, *node, object, key_path);
        }
        if (t == nullptr) return;
        for (const auto& [key, node] : in_file_order(*t)) {
            if (!used.contains(key)) {
                error(*node, join_path(path, key), node_text(*node), "unknown key",
                      "see docs/config.md for the keys of [" +
                          (path.empty() ? std::string("top level") : path) + "]");
            }
        }
    }

    /// The node as a value of `decl`, checked; false (the error reported) when it is not one.
    bool value(const Declaration& decl, const toml::node& node, const std::string& path,
               Value& out);

  private:
    void entry(const Entry& e, const toml::node& node, void* object, const std::string& path) {
        switch (e.decl.type) {
            case Type::table:
                if (const auto* t = node.as_table()) {
                    table(*e.table, t, origin_of(*t, file()), e.sub(object), path);
                } else {
                    error(node, path, node_text(node), "must be a table", e.decl.meaning);
                }
                return;
            case Type::named_tables: {
                const auto* t = node.as_table();
                if (t == nullptr) {
                    error(node, path, node_text(node), "must be a table", e.decl.meaning);
                    return;
                }
                for (const auto& [name, child] : in_file_order(*t)) {
                    const std::string element = join_path(path, name);
                    if (const auto* ct = child->as_table()) {
                        table(*e.table, ct, origin_of(*ct, file()), e.append(object, name),
                              element);
                    } else {
                        error(*child, element, node_text(*child),
                              "must be a table ([" + element + "])", e.decl.meaning);
                    }
                }
                return;
            }
            case Type::array_of_tables: {
                const auto* array = node.as_array();
                if (array == nullptr) {
                    error(node, path, node_text(node),
                          "must be an array of tables ([[" + path + "]])", e.decl.meaning);
                    return;
                }
                for (std::size_t i = 0; i < array->size(); ++i) {
                    const toml::node& child = *array->get(i);
                    const std::string element = index_path(path, i);
                    if (const auto* ct = child.as_table()) {
                        table(*e.table, ct, origin_of(*ct, file()), e.append(object, ""), element);
                    } else {
                        error(child, element, node_text(child), "must be a table", e.decl.meaning);
                    }
                }
                return;
            }
            case Type::named_numbers: {
                const auto* t = node.as_table();
                if (t == nullptr) {
                    error(node, path, node_text(node), "must be a table", e.decl.meaning);
                    return;
                }
                for (const auto& [name, child] : in_file_order(*t)) {
                    Value v;
                    if (value(e.element_decl, *child, join_path(path, name), v)) {
                        e.append(object, name);
                        e.element_set(object, e.size(object) - 1, v);
                    }
                }
                return;
            }
            default: {
                Value v;
                if (value(e.decl, node, path, v)) e.set(object, v);
                return;
            }
        }
    }

    void error(const toml::node& node, const std::string& path, std::string value,
               std::string constraint, std::string meaning) {
        diagnostics_.add(forced_ ? *forced_ : origin_of(node, file()), path, std::move(value),
                         std::move(constraint), std::move(meaning));
    }

    [[nodiscard]] const std::string& file() const { return document_.name(); }

    const Document& document_;
    Diagnostics& diagnostics_;
    std::optional<Origin> forced_;
};

bool Reader::value(const Declaration& decl, const toml::node& node, const std::string& path,
                   Value& out) {
    const bool numeric = decl.type == Type::numbers || decl.type == Type::vector3;
    if (const auto* array = node.as_array(); array != nullptr && numeric) {
        std::vector<double> numbers;
        for (const auto& element : *array) {
            if (const auto* f = element.as_floating_point()) {
                numbers.push_back(f->get());
            } else if (const auto* i = element.as_integer()) {
                numbers.push_back(static_cast<double>(i->get()));
            } else {
                error(element, path, node_text(element), "must be a number",
                      decl.meaning_with_unit());
                return false;
            }
        }
        out = std::move(numbers);
    } else if (array != nullptr && decl.type == Type::strings) {
        std::vector<std::string> strings;
        for (const auto& element : *array) {
            if (const auto* s = element.as_string()) {
                strings.push_back(s->get());
            } else {
                error(element, path, node_text(element), "must be a string",
                      decl.meaning_with_unit());
                return false;
            }
        }
        out = std::move(strings);
    } else if (const auto* b = node.as_boolean()) {
        out = b->get();
    } else if (const auto* i = node.as_integer()) {
        out = static_cast<std::int64_t>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
        out = f->get();
    } else if (const auto* s = node.as_string()) {
        out = s->get();
    } else {
        out = std::monostate{};  // a table, an array where none belongs, a date: no value
    }
    if (auto problem = accept(decl, out)) {
        const toml::node* at = &node;
        if (const auto* array = node.as_array();
            array != nullptr && problem->element >= 0 &&
            static_cast<std::size_t>(problem->element) < array->size()) {
            at = array->get(static_cast<std::size_t>(problem->element));
        }
        error(*at, path, node_text(*at), problem->constraint, decl.meaning_with_unit());
        return false;
    }
    if (decl.type == Type::file) {
        const std::filesystem::path p(std::get<std::string>(out));
        if (!p.empty() && !p.is_absolute()) {
            // Absolute, so the resolved config reads the same file from anywhere.
            out = std::filesystem::absolute(document_.base_dir() / p).lexically_normal().string();
        }
    }
    return true;
}

void run_checks(const Table& schema, const void* object, const std::string& path,
                const SourceMap& where, Diagnostics& diagnostics) {
    for (const Entry& e : schema.entries) {
        if (!e.applies(object)) continue;
        const std::string key_path = join_path(path, e.decl.key);
        switch (e.decl.type) {
            case Type::table:
                run_checks(*e.table, e.sub_of(object), key_path, where, diagnostics);
                break;
            case Type::named_tables:
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    run_checks(*e.table, e.element_of(object, i),
                               join_path(key_path, e.element_name(object, i)), where, diagnostics);
                }
                break;
            case Type::array_of_tables:
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    run_checks(*e.table, e.element_of(object, i), index_path(key_path, i), where,
                               diagnostics);
                }
                break;
            default:
                break;
        }
    }
    for (const Check& c : schema.checks) {
        bool blocked = diagnostics.has_error_within(path);
        for (const auto& need : c.needs) blocked = blocked || diagnostics.has_error_within(need);
        if (blocked) continue;
        for (const auto& v : c.run(object)) {
            const auto mapped = map_leaf_key(schema, v.key);
            const std::string key = append_path(path, mapped ? mapped->key : v.key);
            if (diagnostics.has_error_covering(key)) continue;  // one message per key
            const std::string meaning =
                mapped && mapped->decl != nullptr ? mapped->decl->meaning_with_unit() : v.meaning;
            diagnostics.add(where.locate(key), key, v.value, v.constraint, meaning);
        }
    }
}

}  // namespace

void read(const Table& root, const Document& document, void* object, Diagnostics& diagnostics) {
    Reader reader(document, diagnostics);
    reader.table(root, &document.tree().root, {document.name(), 1, 1}, object, "");
}

bool value_from_text(const Declaration& decl, std::string_view text, const std::string& path,
                     const Origin& origin, Diagnostics& diagnostics, Value& out) {
    // As TOML when it is a TOML value (0.45, 3, true, "name", [0, 0, 1]); else the bare word
    // (linear-steady-state, automatic), which only a name or an automatic key takes.
    // One value on one line: "0.5\n[x]\ny = 1" would parse, and all but its first line be
    // dropped unseen.
    if (text.find_first_of("\r\n") != std::string_view::npos) {
        diagnostics.add(origin, path, quoted(text), "must be one value on one line",
                        decl.meaning_with_unit());
        return false;
    }
    std::shared_ptr<const Document> parsed;
    try {
        parsed = Document::parse_text("value = " + std::string(text), origin.file);
    } catch (const ConfigException&) {
        if (!plain_word(text)) {
            diagnostics.add(origin, path, quoted(text),
                            "must be a TOML value or a plain word (UTF-8, no control characters)",
                            decl.meaning_with_unit());
            return false;
        }
        out = std::string(text);
        if (auto problem = accept(decl, out)) {
            diagnostics.add(origin, path, std::string(text), problem->constraint,
                            decl.meaning_with_unit());
            return false;
        }
        return true;
    }
    Reader reader(*parsed, diagnostics);
    reader.place_all_at(origin);
    const toml::node* node = parsed->tree().root.get("value");
    return node != nullptr && reader.value(decl, *node, path, out);
}

void check(const Table& root, const void* object, const SourceMap& where,
           Diagnostics& diagnostics) {
    run_checks(root, object, "", where, diagnostics);
}

}  // namespace sb::config

// Writing a typed config: resolved TOML, canonical text, identity hash.
#include "config/write.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace sb::config {
namespace {

/// True when the value is not written at all: an absent optional key.
bool absent(const Declaration& d, const Value& v) {
    if (d.presence == Presence::automatic) return false;
    if (std::holds_alternative<std::monostate>(v)) return true;
    if (d.presence == Presence::optional) {
        if (const auto* s = std::get_if<std::string>(&v)) return s->empty();
    }
    return false;
}

bool has_values(const Table& table, const void* object) {
    return std::any_of(table.entries.begin(), table.entries.end(), [&](const Entry& e) {
        return e.decl.is_value() && e.applies(object) &&
               !absent(e.decl, effective_value(table, e, object));
    });
}

class TomlWriter {
  public:
    explicit TomlWriter(std::ostringstream& out) : out_(out) {}

    void table(const Table& schema, const void* object, const std::string& path,
               bool array_element) {
        if (array_element) {
            out_ << "\n[[" << path << "]]\n";
        } else if (!path.empty() && has_values(schema, object)) {
            out_ << "\n[" << path << "]\n";
        }
        for (const Entry& e : schema.entries) {
            if (!e.decl.is_value() || !e.applies(object)) continue;
            const Value v = effective_value(schema, e, object);
            if (absent(e.decl, v)) continue;
            out_ << key_text(e.decl.key) << " = " << value_text(v) << '\n';
        }
        for (const Entry& e : schema.entries) {
            if (e.decl.is_value() || !e.applies(object)) continue;
            const std::string key_path = join_path(path, e.decl.key);
            switch (e.decl.type) {
                case Type::table:
                    table(*e.table, e.sub_of(object), key_path, false);
                    break;
                case Type::named_tables:
                    for (std::size_t i = 0; i < e.size(object); ++i) {
                        table(*e.table, e.element_of(object, i),
                              join_path(key_path, e.element_name(object, i)), false);
                    }
                    break;
                case Type::array_of_tables:
                    for (std::size_t i = 0; i < e.size(object); ++i) {
                        table(*e.table, e.element_of(object, i), key_path, true);
                    }
                    break;
                case Type::named_numbers:
                    if (e.size(object) > 0) {
                        out_ << "\n[" << key_path << "]\n";
                        for (std::size_t i = 0; i < e.size(object); ++i) {
                            out_ << key_text(e.element_name(object, i)) << " = "
                                 << value_text(e.element_get(object, i)) << '\n';
                        }
                    }
                    break;
                default:
                    break;
            }
        }
    }

  private:
    std::ostringstream& out_;
};

std::string file_identity(const std::string& name) {
    if (name.empty()) return config::quoted("");
    std::ifstream in(name, std::ios::binary);
    if (!in) return config::quoted("unreadable");
    std::ostringstream content;
    content << in.rdbuf();
    return config::quoted("content " + fnv1a_hex(content.str()));
}

void collect(const Table& schema, const void* object, const std::string& path,
             std::vector<std::string>& lines) {
    for (const Entry& e : schema.entries) {
        if (!e.applies(object)) continue;
        const std::string key_path = join_path(path, e.decl.key);
        switch (e.decl.type) {
            case Type::table:
                collect(*e.table, e.sub_of(object), key_path, lines);
                break;
            case Type::named_tables:
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    collect(*e.table, e.element_of(object, i),
                            join_path(key_path, e.element_name(object, i)), lines);
                }
                break;
            case Type::array_of_tables:
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    collect(*e.table, e.element_of(object, i), index_path(key_path, i), lines);
                }
                break;
            case Type::named_numbers:
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    lines.push_back(join_path(key_path, e.element_name(object, i)) + " = " +
                                    value_text(e.element_get(object, i)));
                }
                break;
            default: {
                const Value v = effective_value(schema, e, object);
                if (absent(e.decl, v)) break;
                const std::string text = e.decl.type == Type::file
                                             ? file_identity(std::get<std::string>(v))
                                             : value_text(v);
                lines.push_back(key_path);
                lines.back().append(" = ").append(text);
                break;
            }
        }
    }
}

}  // namespace

std::string write_toml(const Table& root, const void* object, std::string_view header_comment) {
    std::ostringstream out;
    if (!header_comment.empty()) out << header_comment << '\n';
    TomlWriter(out).table(root, object, "", false);
    return out.str();
}

std::string canonical_text(const Table& root, const void* object) {
    std::vector<std::string> lines;
    collect(root, object, "", lines);
    std::sort(lines.begin(), lines.end());
    std::string text;
    for (const auto& line : lines) text += line + '\n';
    return text;
}

std::string identity_hash(const Table& root, const void* object) {
    // The version line changes whenever the canonical form does, so that a hash is never
    // compared across forms.
    return fnv1a_hex("shakerbench canonical config 1\n" + canonical_text(root, object));
}

std::string fnv1a_hex(std::string_view text) {
    std::uint64_t h = 14695981039346656037ULL;  // FNV-1a 64-bit offset basis
    for (const char c : text) {
        h ^= static_cast<unsigned char>(c);
        h *= 1099511628211ULL;  // FNV 64-bit prime
    }
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
    return buffer;
}

}  // namespace sb::config

// The key reference, generated from the declarations.
#include "config/reference.hpp"

#include <algorithm>
#include <map>

namespace sb::config {
namespace {

std::string shown_value(const Declaration& d, const Value& v) {
    if (std::holds_alternative<std::monostate>(v)) {
        return d.presence == Presence::automatic ? std::string(kAutomatic) : "absent";
    }
    return value_text(v);
}

void rows(const Table& schema, const void* object, const std::string& path,
          std::vector<KeyRow>& out) {
    for (const Entry& e : schema.entries) {
        if (object != nullptr && !e.applies(object)) continue;
        const std::string key_path = join_path(path, e.decl.key);
        switch (e.decl.type) {
            case Type::table:
                rows(*e.table, object != nullptr ? e.sub_of(object) : nullptr, key_path, out);
                break;
            case Type::named_tables:
            case Type::array_of_tables:
                if (object == nullptr) {
                    rows(*e.table, nullptr,
                         e.decl.type == Type::named_tables ? key_path + ".NAME" : key_path + "[i]",
                         out);
                    break;
                }
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    rows(*e.table, e.element_of(object, i),
                         e.decl.type == Type::named_tables
                             ? join_path(key_path, e.element_name(object, i))
                             : index_path(key_path, i),
                         out);
                }
                break;
            case Type::named_numbers:
                if (object == nullptr) {
                    out.push_back({key_path + ".NAME", &e.element_decl, "-"});
                    break;
                }
                for (std::size_t i = 0; i < e.size(object); ++i) {
                    out.push_back({join_path(key_path, e.element_name(object, i)), &e.element_decl,
                                   value_text(e.element_get(object, i))});
                }
                break;
            default:
                out.push_back({key_path, &e.decl,
                               object != nullptr
                                   ? shown_value(e.decl, effective_value(schema, e, object))
                                   : e.decl.default_text()});
                break;
        }
    }
}

void tables(const Table& schema, const std::string& path, std::vector<DocumentedTable>& out,
            bool array_element) {
    const bool has_values = std::any_of(schema.entries.begin(), schema.entries.end(),
                                        [](const Entry& e) { return e.decl.is_value(); });
    if (has_values) {
        out.push_back({array_element ? "[[" + path + "]]" : "[" + path + "]", &schema, nullptr});
    }
    for (const Entry& e : schema.entries) {
        const std::string key_path = join_path(path, e.decl.key);
        switch (e.decl.type) {
            case Type::table:
                tables(*e.table, key_path, out, false);
                break;
            case Type::named_tables:
                tables(*e.table, key_path + ".NAME", out, false);
                break;
            case Type::array_of_tables:
                tables(*e.table, key_path, out, true);
                break;
            case Type::named_numbers:
                out.push_back({"[" + key_path + "]", nullptr, &e.element_decl});
                break;
            default:
                break;
        }
    }
}

/// Markdown cell text: no line breaks, no bare '|'.
std::string cell(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '|') {
            out += "\\|";
        } else if (c == '\n') {
            out += ' ';
        } else {
            out += c;
        }
    }
    return out;
}

std::string code(const std::string& text) { return "`" + text + "`"; }

std::string markdown_type(const Declaration& d) {
    if (d.type == Type::choice) {
        std::string list;
        for (const auto& c : d.choices)
            list += (list.empty() ? "" : ", ") + code(config::quoted(c));
        return list;
    }
    std::string text = d.type_text();
    const std::string automatic = " or " + config::quoted(kAutomatic);
    if (const auto at = text.find(automatic); at != std::string::npos) {
        text = text.substr(0, at) + " or " + code(config::quoted(kAutomatic));
    }
    return text;
}

std::string markdown_default(const Declaration& d) {
    switch (d.presence) {
        case Presence::required:
            return "required";
        case Presence::optional:
            return "absent";
        case Presence::follows:
            return "as " + code(d.follows);
        case Presence::automatic:
            return code(config::quoted(kAutomatic));
        case Presence::defaulted:
            break;
    }
    return code(value_text(d.default_value));
}

std::string markdown_meaning(const Declaration& d) {
    std::string text = d.doc.empty() ? d.meaning : d.doc;
    if (d.presence == Presence::automatic && !d.automatic.empty()) {
        text += "; " + code(config::quoted(kAutomatic)) + ": " + d.automatic;
    }
    if (d.calibration_range) {
        text += "; calibrated within [" + value_text((*d.calibration_range)[0]) + ", " +
                value_text((*d.calibration_range)[1]) + "] unless `--free` says otherwise";
    }
    if (!d.inactive_reason.empty()) {
        text += " (" + d.inactive_reason + ")";
    }
    return cell(text);
}

std::string row(const std::string& key, const Declaration& d) {
    return "| " + code(key) + " | " + cell(markdown_type(d)) + " | " + cell(markdown_default(d)) +
           " | " + markdown_meaning(d) + " |\n";
}

constexpr std::string_view kOpen = "<!-- keys ";
constexpr std::string_view kOpenEnd = " -->";
constexpr std::string_view kClose = "<!-- /keys -->";

}  // namespace

std::vector<KeyRow> key_rows(const Table& root, const void* object) {
    std::vector<KeyRow> out;
    rows(root, object, "", out);
    return out;
}

std::vector<DocumentedTable> documented_tables(const Table& root) {
    std::vector<DocumentedTable> out;
    tables(root, "", out, false);
    return out;
}

std::string markdown_table(const DocumentedTable& table) {
    std::string text = "| key | type | default | meaning |\n|---|---|---|---|\n";
    if (table.element != nullptr) return text + row("NAME", *table.element);
    for (const Entry& e : table.table->entries) {
        if (e.decl.is_value()) text += row(e.decl.key, e.decl);
    }
    return text;
}

std::string update_key_blocks(std::string_view text, const Table& root,
                              std::vector<std::string>& problems) {
    std::map<std::string, DocumentedTable> by_header;
    for (const auto& t : documented_tables(root)) by_header[t.header] = t;
    std::map<std::string, bool> seen;
    std::string out;
    std::size_t at = 0;
    while (true) {
        const auto open = text.find(kOpen, at);
        if (open == std::string_view::npos) break;
        const auto open_end = text.find(kOpenEnd, open + kOpen.size());
        const auto close = text.find(kClose, open);
        if (open_end == std::string_view::npos || close == std::string_view::npos ||
            close < open_end) {
            problems.push_back("a keys block is not closed by " + std::string(kClose));
            break;
        }
        const std::string header(text.substr(open + kOpen.size(), open_end - open - kOpen.size()));
        out += text.substr(at, open_end + kOpenEnd.size() - at);
        out += '\n';
        const auto it = by_header.find(header);
        if (it == by_header.end()) {
            problems.push_back("the block " + header + " names no declared table");
        } else {
            out += markdown_table(it->second);
            seen[header] = true;
        }
        at = close;
    }
    out += text.substr(at);
    for (const auto& [header, table] : by_header) {
        if (!seen[header]) problems.push_back("no keys block documents " + header);
    }
    return out;
}

}  // namespace sb::config

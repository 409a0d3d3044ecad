// recording.toml reader (toml++: a conforming TOML parser with source positions) and writer.
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "core/text_file.hpp"
#include "identification/file_error.hpp"
#include "identification/recording_io.hpp"

namespace sb::identification {

namespace {

[[noreturn]] void fail(const std::string& file, const toml::source_region& where,
                       const std::string& message) {
    throw FileError(file, static_cast<int>(where.begin.line), static_cast<int>(where.begin.column),
                    message);
}

std::string get_string(const std::string& file, const toml::key& key, const toml::node& node,
                       const std::string& path) {
    if (!node.is_string())
        fail(file, node.source(), "'" + path + "." + std::string(key.str()) + "' must be a string");
    return std::string(*node.value<std::string>());
}

std::string one_of(const std::string& file, const toml::node& node, const std::string& key_path,
                   const std::string& value, const std::vector<std::string>& allowed) {
    if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : " | ") + a;
        fail(file, node.source(), "'" + key_path + "' = \"" + value + "\" must be one of " + list);
    }
    return value;
}

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        out += c;
    }
    return out;
}

std::string role_name(ChannelRole r) {
    switch (r) {
        case ChannelRole::reference:
            return "reference";
        case ChannelRole::control:
            return "control";
        case ChannelRole::response:
            return "response";
    }
    return "response";
}

}  // namespace

Recording read_recording_toml(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::filesystem::exists(path)) throw FileError(file, 0, 0, "file not found");
    toml::table root;
    try {
        root = toml::parse_file(file);
    } catch (const toml::parse_error& e) {
        fail(file, e.source(), std::string(e.description()));
    }
    Recording rec;
    bool have_recording = false;
    for (auto&& [key, node] : root) {
        if (key.str() == "recording") {
            have_recording = true;
            const auto* t = node.as_table();
            if (t == nullptr) fail(file, node.source(), "'recording' must be a table");
            for (auto&& [k, v] : *t) {
                const std::string name(k.str());
                const std::string value = get_string(file, k, v, "recording");
                if (name == "name")
                    rec.info.name = value;
                else if (name == "kind")
                    rec.info.kind =
                        one_of(file, v, "recording.kind", value, {"measured", "simulated"});
                else if (name == "excitation")
                    rec.info.excitation =
                        one_of(file, v, "recording.excitation", value, {"force", "base"});
                else if (name == "description")
                    rec.info.description = value;
                else
                    fail(file, k.source(),
                         "unknown key 'recording." + name +
                             "' (known: name, kind, excitation, description)");
            }
        } else if (key.str() == "channels") {
            const auto* t = node.as_table();
            if (t == nullptr) fail(file, node.source(), "'channels' must be a table of tables");
            std::vector<std::pair<toml::source_position, Channel>> found;
            for (auto&& [ck, cv] : *t) {
                const auto* ct = cv.as_table();
                const std::string path_c = "channels." + std::string(ck.str());
                if (ct == nullptr) fail(file, cv.source(), "'" + path_c + "' must be a table");
                Channel ch;
                ch.name = std::string(ck.str());
                bool have_role = false;
                for (auto&& [k, v] : *ct) {
                    const std::string name(k.str());
                    const std::string value = get_string(file, k, v, path_c);
                    if (name == "quantity")
                        ch.quantity = one_of(
                            file, v, path_c + ".quantity", value,
                            {"force", "acceleration", "velocity", "displacement", "voltage"});
                    else if (name == "unit")
                        ch.unit = value;
                    else if (name == "location")
                        ch.location = value;
                    else if (name == "role") {
                        have_role = true;
                        const auto r = one_of(file, v, path_c + ".role", value,
                                              {"reference", "control", "response"});
                        ch.role = r == "reference" ? ChannelRole::reference
                                  : r == "control" ? ChannelRole::control
                                                   : ChannelRole::response;
                    } else {
                        fail(file, k.source(),
                             "unknown key '" + path_c + "." + name +
                                 "' (known: quantity, unit, location, role)");
                    }
                }
                if (ch.quantity.empty())
                    fail(file, ck.source(), "'" + path_c + "' has no 'quantity'");
                if (!have_role) fail(file, ck.source(), "'" + path_c + "' has no 'role'");
                found.emplace_back(ck.source().begin, std::move(ch));
            }
            // toml++ tables are ordered by key; channels keep the order of the file.
            std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
                return a.first.line < b.first.line ||
                       (a.first.line == b.first.line && a.first.column < b.first.column);
            });
            const Channel* reference = nullptr;
            const Channel* control = nullptr;
            for (auto& [pos, ch] : found) {
                const toml::source_region where{pos, pos, nullptr};
                if (ch.role == ChannelRole::reference) {
                    if (reference != nullptr)
                        fail(file, where,
                             "two reference channels: '" + reference->name + "' and '" + ch.name +
                                 "' (exactly one is allowed)");
                    reference = &ch;
                }
                if (ch.role == ChannelRole::control) {
                    if (control != nullptr)
                        fail(file, where,
                             "two control channels: '" + control->name + "' and '" + ch.name +
                                 "' (at most one is allowed)");
                    control = &ch;
                }
            }
            for (auto& f : found) rec.channels.push_back(std::move(f.second));
            if (reference == nullptr)
                fail(file, node.source(),
                     "no channel has role = \"reference\" (exactly one is required)");
        } else {
            fail(file, key.source(),
                 "unknown table '" + std::string(key.str()) + "' (known: recording, channels)");
        }
    }
    if (!have_recording) throw FileError(file, 1, 1, "missing table [recording]");
    if (rec.channels.empty()) throw FileError(file, 1, 1, "missing tables [channels.NAME]");
    return rec;
}

void write_recording_toml(const std::filesystem::path& path, const Recording& rec) {
    std::ostringstream f;
    f << "[recording]\n"
      << "name = \"" << escape(rec.info.name) << "\"\n"
      << "kind = \"" << escape(rec.info.kind) << "\"\n"
      << "excitation = \"" << escape(rec.info.excitation) << "\"\n"
      << "description = \"" << escape(rec.info.description) << "\"\n";
    for (const auto& ch : rec.channels) {
        f << "\n[channels." << ch.name << "]\n"
          << "quantity = \"" << escape(ch.quantity) << "\"\n"
          << "unit = \"" << escape(ch.unit) << "\"\n"
          << "location = \"" << escape(ch.location) << "\"\n"
          << "role = \"" << role_name(ch.role) << "\"\n";
    }
    write_file_atomically(path, f.str());
}

}  // namespace sb::identification

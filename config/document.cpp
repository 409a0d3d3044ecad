// Parsing config files and locating values in them.
#include "config/document.hpp"

#include <system_error>

#include "config/toml_tree.hpp"

namespace sb::config {

Document::Document(std::unique_ptr<Tree> tree, std::string name, std::filesystem::path base_dir)
    : tree_(std::move(tree)), name_(std::move(name)), base_dir_(std::move(base_dir)) {}

Document::~Document() = default;

namespace {

ConfigException syntax_error(const std::string& name, const toml::parse_error& err) {
    ConfigError e;
    e.file = name;
    e.line = static_cast<int>(err.source().begin.line);
    e.column = static_cast<int>(err.source().begin.column);
    e.key_path = "(syntax)";
    e.constraint = std::string(err.description());
    e.meaning = "not valid TOML";
    return ConfigException({e});
}

}  // namespace

std::shared_ptr<const Document> Document::parse_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        ConfigError e;
        e.file = path.string();
        e.key_path = "(file)";
        e.constraint = "cannot be read";
        e.meaning = "no such config file";
        throw ConfigException({e});
    }
    try {
        auto tree = std::make_unique<Tree>();
        tree->root = toml::parse_file(path.string());
        return std::shared_ptr<const Document>(
            new Document(std::move(tree), path.string(), path.parent_path()));
    } catch (const toml::parse_error& err) {
        throw syntax_error(path.string(), err);
    }
}

std::shared_ptr<const Document> Document::parse_text(std::string_view text, std::string name,
                                                     std::filesystem::path base_dir) {
    try {
        auto tree = std::make_unique<Tree>();
        tree->root = toml::parse(text, name);
        if (base_dir.empty()) base_dir = std::filesystem::current_path();
        return std::shared_ptr<const Document>(
            new Document(std::move(tree), std::move(name), std::move(base_dir)));
    } catch (const toml::parse_error& err) {
        throw syntax_error(name, err);
    }
}

bool split_path(std::string_view path, std::vector<PathPart>& parts) {
    parts.clear();
    std::size_t i = 0;
    bool expect_name = true;
    while (i < path.size()) {
        if (path[i] == '[') {
            const auto close = path.find(']', i);
            if (close == std::string_view::npos || close == i + 1 || parts.empty()) return false;
            std::size_t index = 0;
            for (std::size_t k = i + 1; k < close; ++k) {
                if (path[k] < '0' || path[k] > '9' || index > 100000000) return false;
                index = index * 10 + static_cast<std::size_t>(path[k] - '0');
            }
            parts.push_back({"", true, index});
            i = close + 1;
            expect_name = false;
            continue;
        }
        if (!expect_name) {
            if (path[i] != '.') return false;
            ++i;
            expect_name = true;
            continue;
        }
        std::string name;
        if (path[i] == '"') {
            ++i;
            while (i < path.size() && path[i] != '"') {
                if (path[i] == '\\' && i + 1 < path.size()) ++i;
                name += path[i++];
            }
            if (i >= path.size()) return false;
            ++i;
        } else {
            while (i < path.size() && path[i] != '.' && path[i] != '[') name += path[i++];
            if (name.empty()) return false;
        }
        parts.push_back({std::move(name), false, 0});
        expect_name = false;
    }
    return !parts.empty() && !expect_name;
}

Origin Document::locate(std::string_view path) const {
    Origin at{name_, 1, 1};
    std::vector<PathPart> parts;
    if (!split_path(path, parts)) return at;
    const toml::node* current = &tree_->root;
    for (const auto& part : parts) {
        const toml::node* next = nullptr;
        if (part.is_index) {
            if (const auto* array = current->as_array();
                array != nullptr && part.index < array->size()) {
                next = array->get(part.index);
            }
        } else if (const auto* table = current->as_table()) {
            next = table->get(part.name);
        }
        if (next == nullptr) break;
        current = next;
        at = origin_of(*current, name_);
    }
    return at;
}

}  // namespace sb::config

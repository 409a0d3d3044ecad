// Typed, located reading of TOML config sections.
#include "bench/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sb::bench {

void ConfigDiagnostics::add(const toml::source_region& where, std::string key_path,
                            std::string value, std::string constraint, std::string meaning) {
    ConfigError e;
    e.file = file_;
    e.line = static_cast<int>(where.begin.line);
    e.column = static_cast<int>(where.begin.column);
    e.key_path = std::move(key_path);
    e.value = std::move(value);
    e.constraint = std::move(constraint);
    e.meaning = std::move(meaning);
    errors_.push_back(std::move(e));
}

bool ConfigDiagnostics::has_error_at(std::string_view key_path) const {
    return std::any_of(errors_.begin(), errors_.end(),
                       [&](const ConfigError& e) { return e.key_path == key_path; });
}

void ConfigDiagnostics::throw_if_any() const {
    if (!errors_.empty()) {
        auto sorted = errors_;
        std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
            return std::tie(a.line, a.column) < std::tie(b.line, b.column);
        });
        throw ConfigException(std::move(sorted));
    }
}

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

ConfigDocument ConfigDocument::parse_file(const std::filesystem::path& path) {
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
        return ConfigDocument(toml::parse_file(path.string()), path.string(), path.parent_path());
    } catch (const toml::parse_error& err) {
        throw syntax_error(path.string(), err);
    }
}

ConfigDocument ConfigDocument::parse_text(std::string_view text, std::string name) {
    try {
        return ConfigDocument(toml::parse(text, name), name, std::filesystem::current_path());
    } catch (const toml::parse_error& err) {
        throw syntax_error(name, err);
    }
}

std::string node_text(const toml::node& node) {
    std::ostringstream out;
    if (node.is_table()) {
        return "{...}";
    }
    if (const auto* s = node.as_string()) {
        return "\"" + s->get() + "\"";
    }
    if (const auto* f = node.as_floating_point()) {
        return format_value(f->get());
    }
    node.visit([&out](const auto& n) { out << n; });
    return out.str();
}

Section::Section(const toml::table* table, std::string path, toml::source_region where,
                 ConfigDiagnostics& diagnostics)
    : table_(table), path_(std::move(path)), where_(where), diagnostics_(&diagnostics) {}

Section Section::root(ConfigDocument& document) {
    toml::source_region where;
    where.begin = {1, 1};
    where.end = {1, 1};
    return Section(&document.root(), "", where, document.diagnostics());
}

std::string Section::key_path(std::string_view key) const {
    if (key.empty()) {
        return path_;
    }
    if (path_.empty()) {
        return std::string(key);
    }
    return path_ + "." + std::string(key);
}

bool Section::has(std::string_view key) const { return node(key) != nullptr; }

const toml::node* Section::node(std::string_view key) const {
    if (table_ == nullptr) {
        return nullptr;
    }
    return table_->get(key);
}

const toml::node* Section::lookup(std::string_view key) {
    used_.insert(std::string(key));
    return node(key);
}

void Section::wrong_type(std::string_view key, const toml::node& n, std::string_view expected,
                         std::string_view meaning) {
    diagnostics_->add(n.source(), key_path(key), node_text(n), "must be " + std::string(expected),
                      std::string(meaning));
}

void Section::error(std::string_view key, std::string value, std::string constraint,
                    std::string meaning) {
    const toml::node* n = node(key);
    diagnostics_->add(n != nullptr ? n->source() : where_, key_path(key), std::move(value),
                      std::move(constraint), std::move(meaning));
}

namespace {
std::optional<double> as_number(const toml::node& n) {
    if (const auto* f = n.as_floating_point()) {
        return f->get();
    }
    if (const auto* i = n.as_integer()) {
        return static_cast<double>(i->get());
    }
    return std::nullopt;
}
}  // namespace

std::optional<double> Section::optional_number(std::string_view key, std::string_view meaning) {
    const toml::node* n = lookup(key);
    if (n == nullptr) {
        return std::nullopt;
    }
    auto value = as_number(*n);
    if (!value) {
        wrong_type(key, *n, "a number", meaning);
        return std::nullopt;
    }
    return value;
}

double Section::number(std::string_view key, double fallback, std::string_view meaning) {
    return optional_number(key, meaning).value_or(fallback);
}

double Section::required_number(std::string_view key, std::string_view meaning) {
    if (!has(key)) {
        used_.insert(std::string(key));
        error(key, "", "is required", std::string(meaning));
        return std::nan("");
    }
    return optional_number(key, meaning).value_or(std::nan(""));
}

int Section::integer(std::string_view key, int fallback, std::string_view meaning) {
    const toml::node* n = lookup(key);
    if (n == nullptr) {
        return fallback;
    }
    if (const auto* i = n->as_integer()) {
        const auto v = i->get();
        if (v < -1000000000 || v > 1000000000) {
            error(key, node_text(*n), "must be an integer of reasonable size",
                  std::string(meaning));
            return fallback;
        }
        return static_cast<int>(v);
    }
    wrong_type(key, *n, "an integer", meaning);
    return fallback;
}

bool Section::boolean(std::string_view key, bool fallback, std::string_view meaning) {
    const toml::node* n = lookup(key);
    if (n == nullptr) {
        return fallback;
    }
    if (const auto* b = n->as_boolean()) {
        return b->get();
    }
    wrong_type(key, *n, "true or false", meaning);
    return fallback;
}

std::string Section::string(std::string_view key, std::string fallback, std::string_view meaning) {
    const toml::node* n = lookup(key);
    if (n == nullptr) {
        return fallback;
    }
    if (const auto* s = n->as_string()) {
        return s->get();
    }
    wrong_type(key, *n, "a string", meaning);
    return fallback;
}

std::string Section::required_string(std::string_view key, std::string_view meaning) {
    if (!has(key)) {
        used_.insert(std::string(key));
        error(key, "", "is required", std::string(meaning));
        return {};
    }
    return string(key, {}, meaning);
}

std::string Section::choice(std::string_view key, std::string fallback,
                            const std::vector<std::string>& choices, std::string_view meaning) {
    std::string value = string(key, fallback, meaning);
    if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
        std::string list;
        for (const auto& c : choices) {
            list += (list.empty() ? "" : ", ") + c;
        }
        error(key, "\"" + value + "\"", "must be one of: " + list, std::string(meaning));
        return fallback;
    }
    return value;
}

std::vector<double> Section::numbers(std::string_view key, std::string_view meaning) {
    const toml::node* n = lookup(key);
    std::vector<double> out;
    if (n == nullptr) {
        return out;
    }
    const auto* array = n->as_array();
    if (array == nullptr) {
        wrong_type(key, *n, "an array of numbers", meaning);
        return out;
    }
    for (const auto& element : *array) {
        auto v = as_number(element);
        if (!v) {
            diagnostics_->add(element.source(), key_path(key), node_text(element),
                              "must be a number", std::string(meaning));
            continue;
        }
        out.push_back(*v);
    }
    return out;
}

std::vector<std::string> Section::strings(std::string_view key, std::string_view meaning) {
    const toml::node* n = lookup(key);
    std::vector<std::string> out;
    if (n == nullptr) {
        return out;
    }
    const auto* array = n->as_array();
    if (array == nullptr) {
        wrong_type(key, *n, "an array of strings", meaning);
        return out;
    }
    for (const auto& element : *array) {
        if (const auto* text = element.as_string()) {
            out.push_back(text->get());
        } else {
            diagnostics_->add(element.source(), key_path(key), node_text(element),
                              "must be a string", std::string(meaning));
        }
    }
    return out;
}

Eigen::Vector3d Section::vector3(std::string_view key, const Eigen::Vector3d& fallback,
                                 std::string_view meaning) {
    if (!has(key)) {
        used_.insert(std::string(key));
        return fallback;
    }
    const auto values = numbers(key, meaning);
    if (values.size() != 3) {
        error(key, node_text(*node(key)), "must be an array of 3 numbers", std::string(meaning));
        return fallback;
    }
    return {values[0], values[1], values[2]};
}

Section Section::table(std::string_view key, std::string_view meaning) {
    const toml::node* n = lookup(key);
    if (n == nullptr) {
        return Section(nullptr, key_path(key), where_, *diagnostics_);
    }
    if (const auto* t = n->as_table()) {
        return Section(t, key_path(key), t->source(), *diagnostics_);
    }
    wrong_type(key, *n, "a table", meaning);
    return Section(nullptr, key_path(key), n->source(), *diagnostics_);
}

std::vector<std::pair<std::string, Section>> Section::named_tables(std::string_view meaning) {
    std::vector<std::pair<std::string, Section>> out;
    if (table_ == nullptr) {
        return out;
    }
    for (const auto& [key, value] : *table_) {
        const std::string name(key.str());
        if (const auto* t = value.as_table()) {
            used_.insert(name);
            out.emplace_back(name, Section(t, key_path(name), t->source(), *diagnostics_));
        }
    }
    (void)meaning;
    return out;
}

std::vector<std::pair<std::string, double>> Section::named_numbers(std::string_view meaning) {
    std::vector<std::pair<std::string, double>> out;
    if (table_ == nullptr) {
        return out;
    }
    for (const auto& [key, value] : *table_) {
        const std::string name(key.str());
        used_.insert(name);
        auto v = as_number(value);
        if (!v) {
            wrong_type(name, value, "a number", meaning);
            continue;
        }
        out.emplace_back(name, *v);
    }
    // toml++ keeps keys sorted; order by position in the file, which is what users wrote.
    std::stable_sort(out.begin(), out.end(), [this](const auto& a, const auto& b) {
        const auto& sa = node(a.first)->source().begin;
        const auto& sb = node(b.first)->source().begin;
        return std::tie(sa.line, sa.column) < std::tie(sb.line, sb.column);
    });
    return out;
}

std::vector<Section> Section::array_of_tables(std::string_view key, std::string_view meaning) {
    const toml::node* n = lookup(key);
    std::vector<Section> out;
    if (n == nullptr) {
        return out;
    }
    const auto* array = n->as_array();
    if (array == nullptr) {
        wrong_type(key, *n, "an array of tables ([[" + key_path(key) + "]])", meaning);
        return out;
    }
    for (std::size_t i = 0; i < array->size(); ++i) {
        const auto& element = (*array)[i];
        const std::string path = key_path(key) + "[" + std::to_string(i) + "]";
        if (const auto* t = element.as_table()) {
            out.emplace_back(t, path, t->source(), *diagnostics_);
        } else {
            diagnostics_->add(element.source(), path, node_text(element), "must be a table",
                              std::string(meaning));
        }
    }
    return out;
}

namespace {
/// Walks a leaf-module key path ("masses[2].x_m", "supports.root.kind") as far as it exists.
const toml::node* deepest_node(const toml::table* table, std::string_view key_path) {
    const toml::node* current = table;
    const toml::node* found = nullptr;
    std::size_t start = 0;
    while (current != nullptr && start <= key_path.size()) {
        std::size_t end = key_path.find('.', start);
        if (end == std::string_view::npos) {
            end = key_path.size();
        }
        std::string_view part = key_path.substr(start, end - start);
        std::optional<std::size_t> index;
        if (const auto bracket = part.find('['); bracket != std::string_view::npos) {
            index = static_cast<std::size_t>(
                std::stoul(std::string(part.substr(bracket + 1, part.size() - bracket - 2))));
            part = part.substr(0, bracket);
        }
        const auto* t = current->as_table();
        if (t == nullptr) {
            break;
        }
        const toml::node* next = t->get(part);
        if (next != nullptr && index) {
            const auto* array = next->as_array();
            next = (array != nullptr && *index < array->size()) ? array->get(*index) : nullptr;
        }
        if (next == nullptr) {
            break;
        }
        found = next;
        current = next;
        start = end + 1;
    }
    return found;
}
}  // namespace

void Section::report(const Violations& violations) {
    for (const auto& v : violations) {
        if (diagnostics_->has_error_at(key_path(v.key))) {
            continue;  // already reported when read (wrong type, missing): one message per key
        }
        const toml::node* n = deepest_node(table_, v.key);
        diagnostics_->add(n != nullptr ? n->source() : where_, key_path(v.key), v.value,
                          v.constraint, v.meaning);
    }
}

void Section::finish() {
    if (table_ == nullptr) {
        return;
    }
    for (const auto& [key, value] : *table_) {
        if (used_.find(key.str()) == used_.end()) {
            diagnostics_->add(value.source(), key_path(key.str()), node_text(value), "unknown key",
                              "see docs/config.md for the keys of [" +
                                  (path_.empty() ? std::string("top level") : path_) + "]");
        }
    }
}

}  // namespace sb::bench

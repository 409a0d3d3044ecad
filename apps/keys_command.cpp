// `shakerbench keys`: the declared keys with their types, defaults or values, and meanings;
// with a config, the paths `--set` takes and the config's hash.
#include "keys_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bench/config_schema.hpp"
#include "bench/resolved_config.hpp"
#include "config/reference.hpp"
#include "load_config.hpp"

namespace sb::apps {
namespace {

struct KeysOptions {
    std::string config;
    std::vector<std::string> overrides;
    bool defaults = false;
};

void print_rows(const std::vector<config::KeyRow>& rows) {
    std::size_t width = 0;
    for (const auto& r : rows) width = std::max(width, r.path.size() + 3 + r.value.size());
    width = std::min<std::size_t>(width, 72);
    for (const auto& r : rows) {
        std::string line = r.path + " = " + r.value;
        if (line.size() < width) line.append(width - line.size(), ' ');
        std::cout << line << "  # " << r.decl->type_text() << "; " << r.decl->meaning << '\n';
    }
}

int run_keys(const KeysOptions& options) {
    const auto& schema = bench::campaign_schema();
    if (options.defaults) {
        std::cout << "# Every key of a campaign config with its default (NAME: a name of your "
                     "choice, [i]: an index).\n";
        print_rows(config::key_rows(schema, nullptr));
        return 0;
    }
    int exit_code = 0;
    const auto config = load_config_or_report(options.config, options.overrides, exit_code);
    if (!config) return exit_code;
    std::cout << "# The keys of " << config->source << " with their values; change one with "
              << "--set KEY=VALUE.\n";
    print_rows(config::key_rows(schema, &*config));
    std::cout << "# config_hash = \"" << bench::config_hash(*config) << "\"\n";
    return 0;
}

}  // namespace

void register_keys_command(CLI::App& app, int& exit_code) {
    auto options = std::make_shared<KeysOptions>();
    CLI::App* cmd = app.add_subcommand(
        "keys",
        "List the keys of CONFIG (default: the built-in paper-000 H-0 campaign) by dotted path "
        "with their values, types and meanings: the paths --set takes. With --defaults, every "
        "key any config can have, with its default.");
    cmd->add_option("config", options->config, "campaign config (TOML)");
    add_set_option(*cmd, options->overrides);
    cmd->add_flag("--defaults", options->defaults,
                  "every declared key with its default instead of a config's values");
    cmd->callback([options, &exit_code] { exit_code = run_keys(*options); });
}

}  // namespace sb::apps

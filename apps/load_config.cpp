// Loading a config for a subcommand, reporting every error.
#include "load_config.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "config/errors.hpp"

namespace sb::apps {

std::optional<bench::CampaignConfig> load_config_or_report(
    const std::string& path, const std::vector<std::string>& overrides, int& exit_code,
    std::ostream& errors) {
    try {
        auto config = path.empty() ? bench::load_campaign_config_text(bench::builtin_config_text(),
                                                                      bench::kBuiltinConfigName)
                                   : bench::load_campaign_config(path);
        bench::apply_overrides(config, overrides, "--set");
        return config;
    } catch (const config::ConfigException& e) {
        errors << e.what() << '\n';
        errors << "shakerbench: " << e.errors().size() << " error"
               << (e.errors().size() == 1 ? "" : "s") << " in the config; nothing was run.\n";
        exit_code = config::kExitBadInput;
        return std::nullopt;
    }
}

void add_set_option(CLI::App& command, std::vector<std::string>& overrides) {
    command
        .add_option("--set", overrides,
                    "KEY=VALUE: change the config value at a dotted path, checked as if the "
                    "file held it (repeatable; `shakerbench keys CONFIG` lists the keys)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
}

std::string overrides_text(const std::vector<std::string>& overrides) {
    std::string text;
    for (const auto& o : overrides) {
        std::string quoted = "'";
        for (const char c : o) {
            quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
        }
        text += " --set " + quoted + "'";
    }
    return text;
}

}  // namespace sb::apps

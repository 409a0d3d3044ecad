// Loading a config for a subcommand, reporting every error.
#include "load_config.hpp"

#include <iostream>

#include "bench/config_errors.hpp"

namespace sb::apps {

std::optional<bench::CampaignConfig> load_config_or_report(const std::string& path,
                                                           int& exit_code) {
    try {
        if (path.empty()) {
            return bench::load_campaign_config_text(bench::builtin_config_text(),
                                                    bench::kBuiltinConfigName);
        }
        return bench::load_campaign_config(path);
    } catch (const bench::ConfigException& e) {
        std::cerr << e.what() << '\n';
        std::cerr << "shakerbench: " << e.errors().size() << " error"
                  << (e.errors().size() == 1 ? "" : "s") << " in the config; nothing was run.\n";
        exit_code = bench::kExitBadInput;
        return std::nullopt;
    }
}

}  // namespace sb::apps

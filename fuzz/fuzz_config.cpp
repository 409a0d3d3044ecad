// Fuzz target: a campaign config as text, then `--set` assignments from the same input, as
// `shakerbench run CONFIG --set ...` reads them. A clean end is a config or
// config::ConfigException; anything else escaping is a bug of the reader. A config that loads
// must also write a resolved config that reads back to the same hash (a value the resolved
// file cannot carry would be a silent change of the campaign).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/resolved_config.hpp"
#include "config/errors.hpp"

namespace {

/// After this line, one KEY=VALUE assignment per line (what --set takes).
constexpr std::string_view kSetMarker = "\n#--set\n";
constexpr std::size_t kMaxAssignments = 4;

std::vector<std::string> assignments_of(std::string_view rest) {
    std::vector<std::string> out;
    while (!rest.empty() && out.size() < kMaxAssignments) {
        const auto end = rest.find('\n');
        out.emplace_back(rest.substr(0, end));
        if (end == std::string_view::npos) break;
        rest.remove_prefix(end + 1);
    }
    return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const auto marker = input.find(kSetMarker);
    const std::string_view text = input.substr(0, marker);
    const auto assignments = marker == std::string_view::npos
                                 ? std::vector<std::string>{}
                                 : assignments_of(input.substr(marker + kSetMarker.size()));
    sb::bench::CampaignConfig config;
    try {
        config = sb::bench::load_campaign_config_text(text, "fuzz.toml");
    } catch (const sb::config::ConfigException&) {
        return 0;
    }
    try {
        sb::bench::apply_overrides(config, assignments);
    } catch (const sb::config::ConfigException&) {
        // A refused assignment leaves the config as it was: the check below still holds.
    }
    const std::string resolved = sb::bench::resolved_config_toml(config);
    const std::string hash = sb::bench::config_hash(config);
    try {
        const auto again = sb::bench::load_campaign_config_text(resolved, "resolved.toml");
        if (sb::bench::config_hash(again) == hash) return 0;
        std::fprintf(stderr, "the resolved config reads back to another hash:\n%s\n",
                     resolved.c_str());
    } catch (const sb::config::ConfigException& e) {
        std::fprintf(stderr, "the resolved config does not read back:\n%s\n%s\n", e.what(),
                     resolved.c_str());
    }
    std::abort();
}

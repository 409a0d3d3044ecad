// The whole campaign config: what `shakerbench` reads from one TOML file.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "bench/campaign_spec.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// Everything a config file describes, in SI, validated.
struct CampaignConfig {
    std::string name;         ///< [campaign] name
    std::string description;  ///< [campaign] description
    structure::StructureSpec structure;
    CampaignSpec campaign;           ///< levels, grid, arrangements, dampers, controller, output
    std::string source;              ///< file name (or "<built-in ...>") for messages
    std::filesystem::path base_dir;  ///< relative paths in the config resolve here
};

/// Reads and validates a config file; every problem found is thrown at once as
/// ConfigException (file:line:col: key = value: constraint (meaning)).
CampaignConfig load_campaign_config(const std::filesystem::path& path);

/// The same from text in memory; `name` stands for the file in messages.
CampaignConfig load_campaign_config_text(std::string_view text, const std::string& name);

/// The built-in default campaign (configs/paper000-h0.toml, compiled in).
std::string_view builtin_config_text();
inline constexpr const char* kBuiltinConfigName = "<built-in configs/paper000-h0.toml>";

}  // namespace sb::bench

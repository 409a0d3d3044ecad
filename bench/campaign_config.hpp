// The whole campaign config: what `shakerbench` reads from one TOML file, every value
// addressable by its dotted path.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bench/campaign_spec.hpp"
#include "bench/physics_spec.hpp"
#include "config/errors.hpp"
#include "config/source_map.hpp"
#include "config/value.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// Everything a config file describes, in SI, validated. Its keys are declared in
/// bench/config_schema.cpp.
struct CampaignConfig {
    std::string name = "campaign";  ///< [campaign] name
    std::string description;        ///< [campaign] description
    structure::StructureSpec structure;
    CampaignSpec campaign;           ///< levels, grid, arrangements, dampers, controller, output
    PhysicsSpec physics;             ///< catalogue physics switched on (none by default)
    std::string source;              ///< file name (or "<built-in ...>") for messages
    std::filesystem::path base_dir;  ///< relative paths in the config resolve here
    config::SourceMap where;         ///< where each value came from: the file, the overrides
};

/// Reads and validates a config file; every problem found is thrown at once as
/// config::ConfigException (file:line:col: key = value: constraint (meaning)).
CampaignConfig load_campaign_config(const std::filesystem::path& path);

/// The same from text in memory; `name` stands for the file in messages.
CampaignConfig load_campaign_config_text(std::string_view text, const std::string& name);

/// A problem found in the value at `key` after the config was read (by a command that plans
/// from it, or in a file it names): reported against the config's file, without a line.
config::ConfigError config_problem(const CampaignConfig& config, std::string key, std::string value,
                                   std::string constraint, std::string meaning);

/// The built-in default campaign (configs/paper000-h0.toml, compiled in).
std::string_view builtin_config_text();
inline constexpr const char* kBuiltinConfigName = "<built-in configs/paper000-h0.toml>";

/// The value at a dotted path ("dampers.pd.contact.sliding_friction",
/// "structure.beam.masses[1].mass_kg") as the bench uses it; std::monostate for an automatic
/// value. Throws config::ConfigException when the path names no value.
config::Value get_value(const CampaignConfig& config, std::string_view path);

/// Sets the value at `path` as if the file had held it: checked against its declaration and
/// with every check across keys, else config::ConfigException and nothing changed. `origin`
/// names where the value came from in messages ("--set", "calibration").
void set_value(CampaignConfig& config, std::string_view path, config::Value value,
               const std::string& origin);

/// The same with the value as command-line text (0.45, linear-steady-state, [0, 0, 1]).
void set_value_text(CampaignConfig& config, std::string_view path, std::string_view text,
                    const std::string& origin);

/// Applies `KEY=VALUE` overrides in order (`--set`), as if the file had held all of them:
/// each checked against its declaration and the checks across keys run once on the result, so
/// values valid only together can come in any order. Any problem throws
/// config::ConfigException naming every key at fault and `origin`; nothing is changed then.
void apply_overrides(CampaignConfig& config, const std::vector<std::string>& assignments,
                     const std::string& origin = "--set");

}  // namespace sb::bench

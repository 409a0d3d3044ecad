// The config values a calibration may change: each a dotted path with its search interval,
// mapped to and from the unit cube the optimisers and the emulator work in.
#pragma once

#include <string>
#include <vector>

#include "bench/campaign_config.hpp"

namespace sb::correlation {

/// One freed config value.
struct FreeParameter {
    std::string path;  ///< dotted path: "dampers.pd.contact.sliding_friction"
    double lo = 0.0;   ///< search interval, in the key's unit
    double hi = 1.0;
    double start = 0.0;   ///< the config's value (clamped into the interval)
    std::string meaning;  ///< from the key's declaration, with its unit
    /// Searched in the logarithm of the value ("KEY=MIN:MAX:log", MIN > 0): for values known
    /// only to within decades (a stiffness), whose effect goes with their ratio.
    bool log_scale = false;

    /// The value at unit-cube coordinate u (clamped to [0, 1]).
    [[nodiscard]] double value_at(double u) const;
    /// The unit-cube coordinate of a value.
    [[nodiscard]] double unit_of(double value) const;
};

/// Parses `--free` items, "KEY=MIN:MAX", "KEY=MIN:MAX:log" or "KEY" (the interval then comes from
/// the key's declaration, config::Declaration::calibration_range). Every key must name a number of
/// `config` (not an automatic or absent one unless the interval is given), MIN < MAX, and the
/// interval must lie within the key's bound. Throws config::ConfigException naming the item and
/// origin ("--free") for each problem, all at once.
std::vector<FreeParameter> parse_free_parameters(const bench::CampaignConfig& config,
                                                 const std::vector<std::string>& items,
                                                 const std::string& origin = "--free");

/// The default free set: the particles' sliding and rolling friction and restitution of every
/// DEM damper of `config` (particle-particle; the wall values follow them unless the config
/// gives its own), each within its declared calibration interval.
std::vector<FreeParameter> default_free_parameters(const bench::CampaignConfig& config);

/// Unit-cube coordinates to values: lo + u (hi - lo), or lo (hi/lo)^u on a log scale, u
/// clamped to [0, 1].
std::vector<double> to_values(const std::vector<FreeParameter>& free, const std::vector<double>& u);
/// Values to unit-cube coordinates.
std::vector<double> to_unit(const std::vector<FreeParameter>& free,
                            const std::vector<double>& values);

/// `config` with the free values set (as if the file had held them, origin "calibration"):
/// every check of the config runs. Throws config::ConfigException when they cannot hold.
bench::CampaignConfig with_values(const bench::CampaignConfig& config,
                                  const std::vector<FreeParameter>& free,
                                  const std::vector<double>& values);

/// "0.45" with enough digits to set the value exactly (17 significant digits).
std::string exact_text(double value);

}  // namespace sb::correlation

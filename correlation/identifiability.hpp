// What the data say about each free parameter: its profile-likelihood interval on the feature
// emulator, whether that makes it identifiable, and which levels inform it.
#pragma once

#include <string>
#include <vector>

#include "correlation/emulator.hpp"

namespace sb::correlation {

/// Profile of the misfit over one parameter (the others at their best for each value), from
/// the emulator.
struct Profile {
    std::vector<double> values;  ///< in the key's unit
    std::vector<double> misfit;  ///< ½ χ²
};

struct ParameterFinding {
    FreeParameter parameter;
    double value = 0.0;  ///< the calibrated value
    /// The 95 % interval: where the profile misfit stays within kProfileThreshold of its
    /// minimum (½ χ²₁(0.95) = 1.92; Pawitan 2001, ch. 2.6) [key's unit].
    double lo95 = 0.0;
    double hi95 = 0.0;
    bool identifiable = false;
    std::string reason;  ///< in words, why (not) identifiable
    Profile profile;
    /// Per arrangement and level (Measurement::selection order): the share of the Fisher
    /// information on this parameter that the level's features carry [-], summing to 1 (all
    /// 0 when the features do not depend on it).
    std::vector<double> information_share;
};

inline constexpr double kProfileThreshold = 1.92;
/// A parameter whose 95 % interval covers more than this share of its search interval is
/// reported as not identifiable [-].
inline constexpr double kIdentifiableShare = 0.5;
/// A parameter whose 95 % interval's half-width exceeds this share of its calibrated value is
/// reported as not identifiable: the data bound it only loosely [-].
inline constexpr double kIdentifiableRelative = 0.25;
/// A 95 % interval that reaches within this share of an end of the search interval is a
/// bound, not an identification: reported as not identifiable, with the bound [-].
inline constexpr double kAtAnEnd = 1e-3;

/// The findings for every free parameter at the calibrated unit-cube point `best_u`.
std::vector<ParameterFinding> assess_identifiability(const FeatureEmulator& emulator,
                                                     const Measurement& measurement,
                                                     const std::vector<FreeParameter>& free,
                                                     const std::vector<double>& best_u);

}  // namespace sb::correlation

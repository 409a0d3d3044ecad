// Where a simulation and a measurement disagree: both reduced to the same features per
// arrangement and level (natural frequency, damping ratio, peak of the FRF and its phase,
// harmonic ratios and drive at the peak), each with its noise floor; per feature the levels
// that disagree beyond that noise and how the residual scales with the level
// (docs/diagnosis.md; the first two steps of a diagnosis).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "correlation/features.hpp"
#include "correlation/scaling_law.hpp"
#include "identification/recording.hpp"

namespace sb::correlation {

enum class LevelFeature {
    natural_frequency,  ///< f_n [Hz] (circle fit, else half-power)
    damping_ratio,      ///< ζ [-] (the same estimator)
    peak_magnitude,     ///< largest |H| over the level's points [FRF unit]
    peak_phase,         ///< arg H at that point [rad]
    h2_ratio,           ///< |X2|/|X1| of the response at that point [-]
    h3_ratio,           ///< |X3|/|X1| [-]
    drive,              ///< |reference| at that point (the force or table motion needed) [its unit]
};
inline constexpr std::size_t kLevelFeatures = 7;
/// "natural frequency", "damping ratio", "peak |H|", "phase at the peak", "H2/H1", "H3/H1",
/// "drive at the peak".
std::string level_feature_name(LevelFeature feature);

/// The features of one arrangement and level: the mean over its fillings, with a standard
/// uncertainty: the scatter of the fillings over √n where there are several and that is
/// larger, else the stated uncertainty (for the harmonic ratios, the FRF's relative one and
/// a floor of kHarmonicFloor). NaN where the recording cannot give a value.
struct LevelFeatureValues {
    std::string arrangement;
    double level_g = 0.0;
    int fillings = 0;
    std::array<double, kLevelFeatures> value{};
    std::array<double, kLevelFeatures> sigma{};
};

/// Harmonic ratios below this are noise in any recording [-].
inline constexpr double kHarmonicFloor = 0.002;

/// Reduces a recording (measured or simulated) to the level features, identified as
/// `shakerbench identify` does, in order of first appearance. Throws what identify_recording
/// throws.
std::vector<LevelFeatureValues> level_feature_values(const identification::Recording& recording,
                                                     const StatedUncertainty& stated);

/// One feature of one arrangement over its levels.
struct FeatureMismatch {
    std::string arrangement;
    LevelFeature feature = LevelFeature::damping_ratio;
    /// Per level present in both (Δ = measured − simulated, σ² = σm² + σs²).
    std::vector<LevelResidual> residuals;
    double chi2 = 0.0;  ///< Σ (Δ/σ)²
    /// χ² beyond its 99 % quantile with one degree of freedom per level: the levels together
    /// disagree beyond the noise.
    bool beyond_noise = false;
    std::vector<double> levels_beyond;  ///< levels with |Δ/σ| > kLevelBeyond [g]
    std::vector<ScalingFit> scaling;    ///< fit_scaling of the residuals, best first
    std::string sentence;               ///< in words, for the report
};

/// A single level disagrees beyond the noise when |Δ/σ| exceeds this (two-sided 99.7 %) [-].
inline constexpr double kLevelBeyond = 3.0;

/// Every feature of every arrangement that both have at some level, those beyond the noise
/// first (largest χ² first), then the others.
std::vector<FeatureMismatch> locate_mismatch(const std::vector<LevelFeatureValues>& measured,
                                             const std::vector<LevelFeatureValues>& simulated);

/// The quantile of χ² with `dof` degrees of freedom at probability `p` (Wilson and Hilferty
/// 1931: accurate to a few parts in a thousand from 2 degrees of freedom, the few per cent
/// at 1 that a noise test can bear).
double chi2_quantile(double p, int dof);

}  // namespace sb::correlation

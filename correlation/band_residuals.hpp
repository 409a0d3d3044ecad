// FRF residuals per frequency band (docs/diagnosis.md): each level's measured points below,
// around and above its resonance compared with the simulation's at the same frequencies. The
// level features say how the modal values disagree; the bands say where along the FRF, which
// the modal values can hide (a curve that is right at its peak and wrong on its flanks).
#pragma once

#include <string>
#include <vector>

#include "correlation/features.hpp"
#include "correlation/mismatch.hpp"

namespace sb::correlation {

enum class FrfBand {
    below,      ///< f < f_n (1 − ζ): the flank the stiffness governs
    resonance,  ///< the half-power band f_n (1 ± ζ): the damping governs the peak
    above,      ///< f > f_n (1 + ζ): the flank the mass governs
};
/// "below the resonance", "around the resonance", "above the resonance".
std::string frf_band_name(FrfBand band);

/// One band of one arrangement and level.
struct BandResidual {
    std::string arrangement;
    double level_g = 0.0;
    FrfBand band = FrfBand::resonance;
    int points = 0;  ///< FRF points in the band (each a magnitude and a phase)
    /// Σ (Δ/σ)² of ln|H| and of the phase over the band's points, Δ = measured − simulated.
    double chi2_magnitude = 0.0;
    double chi2_phase = 0.0;
    /// Mean ln(|H| measured / |H| simulated) [-] (+0.05: the measured 5 % larger) and mean
    /// phase difference [rad].
    double mean_log_ratio = 0.0;
    double mean_phase_rad = 0.0;
    /// χ² of the band (2 per point) beyond its quantile at 1 − 0.01/N, N the bands compared
    /// (Bonferroni: the diagnosis as a whole raises a false alarm at most 1 % of the time).
    bool beyond_noise = false;
    std::string sentence;  ///< in words, for the report
};

/// The bands of every arrangement and level that `measured_levels` gives a natural frequency
/// and a damping ratio for, from the measurement's FRF features and `simulated` (the same
/// features, in the same order); bands without points are left out. Beyond the noise first
/// (largest χ² first), then the others in the measurement's order.
std::vector<BandResidual> band_residuals(const Measurement& measurement,
                                         const SimulatedFeatures& simulated,
                                         const std::vector<LevelFeatureValues>& measured_levels);

}  // namespace sb::correlation

// What a calibration compares: a measurement and a simulation reduced to the same features
// per arrangement and level (natural frequency, damping ratio, and the FRF's log magnitude and
// phase at each measured frequency), each with its uncertainty.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_plan.hpp"
#include "identification/recording.hpp"

namespace sb::correlation {

enum class FeatureKind {
    natural_frequency,  ///< [Hz]
    damping_ratio,      ///< [-]
    log_magnitude,      ///< ln |H| of the FRF at one frequency [-]
    phase,              ///< arg H at one frequency [rad]
};

/// One compared quantity of one arrangement and level, with the measured value.
struct Feature {
    std::string arrangement;
    double level_g = 0.0;
    FeatureKind kind = FeatureKind::damping_ratio;
    double frequency_hz = 0.0;  ///< the FRF's frequency (log_magnitude, phase); else 0
    double value = 0.0;         ///< measured
    /// Standard uncertainty of the measured value: the scatter of repeats (fillings, repeated
    /// points) over the square root of their number where that is larger than the stated
    /// uncertainty, else the stated uncertainty.
    double sigma = 0.0;
    bool sigma_from_repeats = false;
    /// How many repeats (fillings of the bed, repeated points) the value averages [-].
    int repeats = 1;  ///< there were repeats (their scatter may be below the floor)

    /// "H-0 0.5 g damping", "H-0 0.5 g |H| at 6.70 Hz".
    [[nodiscard]] std::string label() const;
};

/// The uncertainty a measurement without repeats is given (stated by the user, else these).
struct StatedUncertainty {
    double damping_relative = 0.05;     ///< of the damping ratio [-]
    double frequency_relative = 0.002;  ///< of the natural frequency [-]
    /// Of |H| (as ln|H|) and of the phase in radians, per FRF point [-].
    double frf_relative = 0.05;
};

/// A measurement as calibration uses it.
struct Measurement {
    std::filesystem::path directory;
    /// What the directory holds: "damping.csv", "points.csv" or "time histories".
    std::string depth;
    std::string response_channel;  ///< the FRF's response channel (empty: damping.csv only)
    /// The quantity of the FRF's reference channel: "force", "voltage" (a shaker's drive),
    /// "acceleration" (a base's); empty with damping.csv only.
    std::string reference_quantity;
    std::string damping_method;  ///< the estimator compared: circle-fit, else half-power
    std::vector<Feature> features;
    /// The arrangements, levels and frequencies a simulation must give: the measured ones
    /// (without points, each level on the config's grid).
    bench::Selection selection;
    std::vector<identification::DampingRow> damping;  ///< the measured damping curve
};

/// Reads a measured recording directory at any depth: recording.toml with points.csv (the
/// FRF's points, their time histories if any) and damping.csv if present, or damping.csv
/// alone. The damping features come from damping.csv when there is one (its seed or repeat
/// scatter with them), else from the points identified as `shakerbench identify` does.
/// Throws identification::FileError for an unreadable file, std::invalid_argument when the
/// directory holds neither, or when nothing can be compared.
Measurement read_measurement(const std::filesystem::path& directory,
                             const StatedUncertainty& stated = {});

/// A simulation reduced to the features of a measurement, in the same order.
struct SimulatedFeatures {
    std::vector<double> value;  ///< NaN where the simulation gives none (a failed estimate)
    /// The simulation's own scatter of each value: over its fillings, over the square root of
    /// their number; 0 with one filling.
    std::vector<double> sigma;
    std::vector<identification::DampingRow> damping;  ///< the simulated damping curve
    int points_flagged = 0;  ///< points left out of the fits (closest, uncertain ...)
    int fillings = 1;        ///< fillings of the bed each value averages [-]
};

/// The features of `measurement` taken from a campaign's result (identified as the
/// measurement: the same response channel, the same estimator).
SimulatedFeatures simulated_features(const bench::CampaignResult& result,
                                     const Measurement& measurement);

/// Whether two levels [g] are the same one (as read back from files: equal to 1e-9).
bool same_level(double a, double b);

/// Residual of one feature in standard deviations: (simulated − measured) / σ, the phase
/// difference wrapped into (−π, π]. σ² = σm² + σs², σs the simulation's scatter of its mean over
/// `simulated_fillings` fillings; σm the measured uncertainty, at least the scatter the bed's
/// own chaos gives a mean over the measurement's repeats (σs² simulated_fillings / repeats):
/// a measured damper is one more filling of the same physics. A missing simulated value counts
/// kMissingResidual.
double residual(const Feature& feature, double simulated, double simulated_sigma,
                int simulated_fillings);
inline constexpr double kMissingResidual = 10.0;

}  // namespace sb::correlation

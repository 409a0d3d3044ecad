// A campaign predicted from describing functions: every stepped-sine point solved directly by
// harmonic balance of the reduced modal structure with the dampers' complex apparent masses,
// the drive set so that the control point holds its RMS target (docs/characterisation.md).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "bench/attachment.hpp"
#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/campaign_plan.hpp"

namespace sb::bench {

/// The describing-function damper `damper` (model = describing-function) in the arrangement
/// of `prepared`, as an attachment at its point: the bed's weight at the centre of a settled
/// bed, the excitation direction. Throws config::ConfigException naming
/// dampers.NAME.characterization_file when the file cannot be read or has no grid for this
/// damper in this arrangement.
Attachment describing_function_attachment(const CampaignConfig& config, const DamperSpec& damper,
                                          const PreparedArrangement& prepared);

/// The config with every damper whose model is dem represented by the describing function of
/// `file` instead (model = describing-function, characterization_file = file,
/// characterization_scale = scale): what `predict --characterization FILE [--scale S]`
/// predicts; its hash says so.
CampaignConfig with_describing_functions(const CampaignConfig& config,
                                         const std::filesystem::path& file, double scale = 1.0);

/// What a prediction needs besides its config.
struct PredictContext {
    Selection selection;  ///< the sweeps to predict; empty: the whole config
    /// Receives progress and warning lines; empty: none.
    std::function<void(const std::string&)> progress;
};

/// A damper point's acceleration harmonics (|a2| + |a3| against |a1|, from the characterised
/// force harmonics through the structure's accelerance at 2w and 3w) above this make a point
/// `uncertain`: the characterisation drove a pure sine [-].
inline constexpr double kHarmonicTrustLimit = 0.1;

/// Fixed-point iterations on the damper amplitudes before a point is `uncertain`, and the
/// relative change that ends them [-].
inline constexpr int kPredictIterations = 100;
inline constexpr double kPredictConvergence = 1e-10;

/// Predicts every point of the sweeps of context.selection (or of the whole config). Every
/// damper must be a describing function or rigid. A point's status: `predicted`, or
/// `extrapolated` when a damper's amplitude or the frequency lies outside its characterised
/// grid (the value held at the grid's edge), or `uncertain` when the amplitudes did not
/// converge, a grid point around it did not settle or the response is strongly non-harmonic
/// (kHarmonicTrustLimit). The result is a campaign's (recording, identified levels, sweeps),
/// written by write_campaign_output like a run's. Throws config::ConfigException when the
/// config cannot be predicted (a DEM damper, base excitation, a bad characterisation file).
CampaignResult predict_campaign(const CampaignConfig& config, const PredictContext& context);

}  // namespace sb::bench

// Natural frequency and damping per arrangement and level of a recording, by every method.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "identification/circle_fit.hpp"
#include "identification/frf.hpp"
#include "identification/half_power.hpp"
#include "identification/modal_estimate.hpp"
#include "identification/rational_fraction.hpp"
#include "identification/recording.hpp"
#include "identification/residual.hpp"

namespace sb::identification {

/// What identify_recording does with points whose controller ended in status `closest`: it
/// never held the target RMS within tolerance and kept the amplitude closest to it, so the
/// point belongs to another level (and, near resonance of a nonlinear specimen, to another
/// FRF). A lab engineer leaves such points out of the fits and says so.
enum class ClosestPolicy {
    skip,  ///< left out of the FRF and therefore of every fit (LevelIdentification::skipped_hz)
    use,   ///< kept like any other point (LevelIdentification::closest_used_hz)
};

/// Options of identify_recording.
struct IdentifyOptions {
    /// Response channel; empty: the control channel, else the first response channel.
    std::string response_channel;
    /// Damping ratio of the bare rig, subtracted from every estimate [-] (0: none).
    double background_damping_ratio = 0.0;
    HalfPowerForm half_power_form = HalfPowerForm::mobility;
    CircleFitOptions circle;                    ///< its `residual` is replaced by `residual`
    RationalFractionOptions rational_fraction;  ///< its `residual` is replaced by `residual`
    /// Residual of other modes, for all three estimators (residual.hpp).
    ResidualOptions residual;
    /// Effective (modal) mass at the response point [kg] for the specific damping capacity
    /// W/T; 0 skips it. Needs force excitation with a force reference.
    double effective_mass_kg = 0.0;
    /// Points with status `closest` (identify_recording only; an FRF has no statuses).
    ClosestPolicy closest = ClosestPolicy::skip;
};

/// Everything identified at one arrangement and level.
struct LevelIdentification {
    std::string arrangement;
    double level_g = 0.0;  ///< [g]
    int filling = 0;       ///< the filling of the bed whose points these are
    std::string channel;   ///< response channel used
    Frf frf;  ///< repeats averaged; force: response/reference, base: (resp − table)/table
    ModalEstimate half_power;
    ModalEstimate circle_fit;
    ModalEstimate rational_fraction;
    /// Specific damping capacity ψ = W/T of paper 003 at the grid point of largest response
    /// [-], background 4πζ_bg subtracted; NaN unless IdentifyOptions::effective_mass_kg > 0.
    /// For a viscous SDOF it equals 4πζ f_n/f at that point.
    double specific_damping_capacity = std::numeric_limits<double>::quiet_NaN();
    double capacity_frequency_hz =
        std::numeric_limits<double>::quiet_NaN();  ///< where ψ is taken [Hz]
    /// Frequencies of the points with status `closest` left out of the FRF (ClosestPolicy::
    /// skip), one per point (a repeat counts), ascending [Hz]. A frequency also measured by a
    /// point that was kept stays on the FRF grid.
    std::vector<double> skipped_hz{};
    /// Frequencies of the points with status `closest` kept in the FRF (ClosestPolicy::use),
    /// one per point, ascending [Hz], so that they are flagged rather than silently used.
    std::vector<double> closest_used_hz{};
    /// The statuses of those points (closest, extrapolated, uncertain), each once, in the
    /// order of kPointStatuses.
    std::vector<std::string> flagged_statuses{};
};

/// "closest", "extrapolated or uncertain": the statuses of the points flagged at a level, for
/// the lines that name them ("closest" when none are known).
inline std::string flagged_status_text(const LevelIdentification& level) {
    std::string text;
    for (std::size_t i = 0; i < level.flagged_statuses.size(); ++i) {
        text += (i == 0 ? "" : " or ") + level.flagged_statuses[i];
    }
    return text.empty() ? std::string("closest") : text;
}

/// The three estimators on one FRF, background subtracted; W/T when `force_reference` (the
/// FRF is response per newton) and options.effective_mass_kg > 0. `channel` is left empty.
LevelIdentification identify_frf(const std::string& arrangement, double level_g, const Frf& frf,
                                 const IdentifyOptions& options, bool force_reference);

/// Groups points by arrangement and level (in order of first appearance), leaves out the
/// points with status `closest` unless options.closest is ClosestPolicy::use, combines
/// repeats (same frequency) by H1 = Σ Y conj(X) / Σ |X|², builds the FRF and runs the three
/// estimators (identify_frf). A level whose points are all left out keeps its place with an
/// empty FRF and estimates that say too-few-points.
/// Force excitation: response/reference in the form of the response quantity (acceleration →
/// accelerance, velocity → mobility, displacement → receptance). Base excitation: the relative
/// transmissibility, exact for a base-excited SDOF. Throws std::invalid_argument (naming the
/// channels) if the response channel does not exist or is the reference.
std::vector<LevelIdentification> identify_recording(const Recording& recording,
                                                    const IdentifyOptions& options = {});

/// damping.csv rows of the successful estimates, one per arrangement, level and method:
/// over several fillings the mean frequency and damping with their sample standard deviation
/// (the seed scatter; 0 for one filling); methods half-power and circle-fit (the two
/// formats.md lists) and, when `include_rational_fraction`, rational-fraction.
std::vector<DampingRow> damping_rows(const std::vector<LevelIdentification>& levels,
                                     bool include_rational_fraction = false);

/// The same per filling (DampingRow::filling set), for a recording of several fillings.
std::vector<DampingRow> filling_damping_rows(const std::vector<LevelIdentification>& levels,
                                             bool include_rational_fraction = false);

}  // namespace sb::identification

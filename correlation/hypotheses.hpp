// The third and fourth steps of a diagnosis (docs/diagnosis.md): the catalogue's physics
// ranked by how their signatures match the located mismatch, the best few switched on and
// fitted on all but the highest level of each arrangement, compared by BIC, and confirmed on
// the held-out levels.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "correlation/calibration.hpp"
#include "correlation/features.hpp"
#include "correlation/physics_catalogue.hpp"

namespace sb::correlation {

struct HypothesisOptions {
    int candidates = 3;  ///< the best-ranked rows with a positive score fitted, at most
    /// The highest levels of each arrangement held out of the fits, when it has at least two
    /// more than these to fit on.
    int held_out_levels = 1;
    /// The fits' search, threads, cache and simulation (the fast prediction where the config
    /// allows it: candidate_simulation()).
    CalibrationOptions calibration;
    /// When the fits ran on a simulation of their own (calibration.simulate), the winner and
    /// the baseline are simulated again by the coupled campaign, describing-function dampers
    /// as the DEM beds they were characterised from (confirm_winner()).
    bool confirm = false;
};

/// The winner and the baseline simulated by the coupled campaign on the measured points:
/// whether what the prediction found holds in the full model.
struct Confirmation {
    std::string simulation;  ///< in words: "the coupled campaign, dampers pd as DEM beds"
    double baseline_fit = 0.0, fit = 0.0;            ///< ½ χ² of the fitted levels
    double baseline_held_out = 0.0, held_out = 0.0;  ///< and of the held-out levels
    bool confirmed = false;  ///< it lowers both as the prediction said (fit and held out)
    std::string sentence;    ///< in words
    std::string error;       ///< why it could not be run; empty when it was
};

/// One candidate, or a pair of them, switched on and fitted.
struct CandidateFit {
    CandidateScore rank;  ///< a pair's: its first row, the scores summed
    /// The catalogue rows switched on: one, or two when no single one explained the mismatch.
    std::vector<const CatalogueEntry*> entries;
    /// "air-drag", "air-drag + background-damping".
    [[nodiscard]] std::string name() const;
    /// "the beam's aerodynamic drag", "... and the rig's background damping".
    [[nodiscard]] std::string left_out() const;
    std::vector<FreeParameter> free;
    std::vector<double> values;              ///< fitted on the fitting levels
    std::vector<ParameterFinding> findings;  ///< their 95 % intervals (when found)
    /// ½ χ² of the features of the fitting levels and of the held-out levels, for the
    /// baseline config and for this candidate at its fitted values.
    double baseline_fit = 0.0, fit = 0.0;
    double baseline_held_out = 0.0, held_out = 0.0;
    /// BIC = χ² + k ln n on the fitting levels, n the effective sample size (two per level:
    /// the modal frequency and damping each level identifies; the FRF points around them are
    /// correlated through those two) [-].
    double baseline_bic = 0.0, bic = 0.0;
    int simulations = 0;
    bench::CampaignConfig improved;  ///< the config with it on at the fitted values
    /// Its simulation at the fitted values on every measured level (held out too), reduced to
    /// the measurement's features, with its damping curve: for the report's plots.
    SimulatedFeatures simulated;
    std::string error;  ///< why it could not be fitted; empty when it was
};

struct HypothesisTest {
    std::vector<CandidateScore> ranking;  ///< every row that applies, best first
    /// Whether pairs of the fitted rows were tried: the best single one left the fitted
    /// levels' χ² above twice their number of features (every pair), or freed two values or
    /// more (the pairs that free no more).
    bool pairs_tried = false;
    /// Per arrangement, its options.held_out_levels highest levels when it has two more.
    std::vector<std::pair<std::string, double>> held_out;
    std::vector<CandidateFit> fits;  ///< the fitted candidates, lowest BIC first
    /// The index of the winner in `fits`: of those that lower the BIC by more than kBicStrong
    /// and the held-out misfit below the baseline's, the one of lowest BIC whose held-out
    /// misfit is within kHeldOutTolerance times the best of them; -1 when none does.
    int winner = -1;
    /// The winner confirmed on the coupled campaign (HypothesisOptions::confirm).
    std::optional<Confirmation> confirmation;
    std::string sentence;  ///< in words
};

/// A BIC lower by this much is strong evidence (Kass and Raftery 1995) [-].
inline constexpr double kBicStrong = 6.0;
/// A fit that predicts the held-out levels more than this many times worse than another
/// strong fit is not the winner, whatever its BIC [-].
inline constexpr double kHeldOutTolerance = 2.0;

/// Strong evidence for a fit: its BIC lower than the baseline's by more than kBicStrong, it
/// was fitted, and (`held_out`: levels were held out) it predicts them better than the
/// baseline.
bool is_strong(const CandidateFit& fit, bool held_out);

/// The winner among `fits` (lowest BIC first): the strong fit of lowest BIC whose held-out
/// misfit is within kHeldOutTolerance times the best strong fit's; -1 when none is strong.
int choose_winner(const std::vector<CandidateFit>& fits, bool held_out);

/// The simulation hypotheses are fitted on: the describing-function prediction of
/// bench/prediction.hpp when every damper of `config` is rigid or a describing function and
/// the structure is driven by a force (milliseconds to seconds per campaign), else empty (the
/// coupled campaign).
Simulation candidate_simulation(const bench::CampaignConfig& config);

/// `config` as the coupled campaign simulates it in full: every describing-function damper as
/// the DEM bed its table was characterised from (its own particles, enclosure and contact
/// keys), with the names of those switched.
bench::CampaignConfig full_model(const bench::CampaignConfig& config,
                                 std::vector<std::string>* switched = nullptr);

/// Ranks the catalogue against `mismatches`, fits the best options.candidates with a positive
/// score (each switched on in a copy of `config`, its keys freed within their intervals) on
/// the measurement without its held-out levels, then every pair of those fitted when the best
/// single one does not reach the noise (those no more complex than it when it does but frees
/// two values or more), and compares them all; with options.confirm, confirms the winner
/// on the coupled campaign. Throws what calibrate
/// throws for the baseline's evaluation; a candidate that cannot be fitted keeps its error.
HypothesisTest test_hypotheses(const bench::CampaignConfig& config, const Measurement& measurement,
                               const std::vector<FeatureMismatch>& mismatches,
                               const HypothesisOptions& options);

}  // namespace sb::correlation

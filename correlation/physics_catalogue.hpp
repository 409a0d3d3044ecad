// The physics catalogue (docs/diagnosis.md): each physics a model may leave out, one row: what
// it is in words, the config keys that switch it on and size it (their search intervals from
// the keys' declarations), and its signature, how it shows in the level features (research
// note on mismatch diagnosis, section 2). Adding a physics is one row here and its model in
// the bench.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bench/campaign_config.hpp"
#include "correlation/mismatch.hpp"

namespace sb::correlation {

/// How a physics moves one feature: the shape of measured − simulated over the level when the
/// simulation leaves it out, and its sign (+1: the measurement's value is larger).
struct FeatureSignature {
    LevelFeature feature = LevelFeature::damping_ratio;
    ScalingShape shape = ScalingShape::constant;
    int sign = +1;
};

struct CatalogueEntry {
    std::string name;      ///< "air-drag"
    std::string left_out;  ///< as the report says it: "the beam's aerodynamic drag"
    std::string description;
    /// The features it moves beyond the noise; the other damping and frequency features it
    /// leaves within the noise.
    std::vector<FeatureSignature> signature;
    /// Turns the physics on in `config` (adds what its keys need) and returns its keys, each
    /// "KEY" (the declared search interval) or "KEY=MIN:MAX" (parse_free_parameters).
    std::function<std::vector<std::string>(bench::CampaignConfig& config)> switch_on;
    /// Whether `config` can take it (a beam for the drag, ...) and is not already modelling
    /// it; empty: always.
    std::function<bool(const bench::CampaignConfig& config)> applies;
    /// The quantity of a measured reference the row turns the model's drive into ("voltage":
    /// a shaker); empty: it leaves the drive as it is. Such a row applies only where the
    /// measurement's reference is that quantity and the model's is not.
    std::string makes_reference;
};

/// The quantity of the reference channel `config` records: "force", "voltage" (through a
/// shaker) or "acceleration" (base excitation).
std::string model_reference_quantity(const bench::CampaignConfig& config);

/// Every row, in a fixed order (ties in a ranking keep it).
const std::vector<CatalogueEntry>& physics_catalogue();

/// The row named `name`; throws std::invalid_argument listing the names otherwise.
const CatalogueEntry& catalogue_entry(std::string_view name);

/// A row scored against located mismatches.
struct CandidateScore {
    const CatalogueEntry* entry = nullptr;
    /// +2 per signature feature beyond the noise with the right sign, +1 more when its shape
    /// fits the residual within 2 of the best BIC; -2 per signature feature with the wrong
    /// sign, -1 per one within the noise; -1 per damping or frequency feature beyond the noise
    /// that the signature leaves alone.
    double score = 0.0;
    std::string reason;  ///< in words
};

/// The rows that apply to `config`, best score first (the catalogue's order among equals).
/// `measured_reference`: the quantity of the measurement's reference channel (empty: unknown,
/// taken as the model's). Where it is not the model's, a row that makes it scores +4 and
/// every other row -4: no physics of the structure turns newtons into volts.
std::vector<CandidateScore> rank_candidates(const bench::CampaignConfig& config,
                                            const std::vector<FeatureMismatch>& mismatches,
                                            const std::string& measured_reference = {});

}  // namespace sb::correlation

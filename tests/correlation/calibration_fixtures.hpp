// Measurements for the calibration tests: a campaign simulated with known values, its points
// perturbed by a known noise, written as a recording directory.
#pragma once

#include <unistd.h>

#include <complex>
#include <filesystem>
#include <random>
#include <string>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/prediction.hpp"
#include "identification/recording_io.hpp"

namespace sb::correlation::testing {

inline std::filesystem::path fresh_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("shakerbench-calibration-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

/// The fast simulation of the tests: every point by harmonic balance (rigid or
/// describing-function dampers only).
inline bench::CampaignResult predict(const bench::CampaignConfig& config,
                                     const bench::Selection& selection, int /*threads*/) {
    bench::PredictContext context;
    context.selection = selection;
    return bench::predict_campaign(config, context);
}

/// The points of `result` with every channel's fundamental multiplied by (1 + noise (a + ib)),
/// a and b standard normal from `seed`, as a measured recording without damping.csv (the
/// damping is identified from the points, as from a lab's recording).
inline void write_noisy_recording(const bench::CampaignResult& result, double noise,
                                  std::uint64_t seed, const std::filesystem::path& dir) {
    identification::Recording recording = result.recording;
    recording.info.kind = "measured";
    recording.damping.clear();
    std::mt19937_64 generator(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (auto& point : recording.points) {
        point.status = "measured";
        for (auto& value : point.values) {
            const std::complex<double> factor(1.0 + noise * normal(generator),
                                              noise * normal(generator));
            value.amplitude *= factor;
            value.rms *= std::abs(factor);
        }
    }
    identification::write_recording(dir, recording);
}

}  // namespace sb::correlation::testing

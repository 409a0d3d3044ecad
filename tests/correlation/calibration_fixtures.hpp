// Measurements for the calibration tests: a campaign simulated with known values, its points
// perturbed by a known noise, written as a recording directory.
#pragma once

#include <unistd.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/prediction.hpp"
#include "correlation/calibration.hpp"
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

// The linear bench of the calibration tests (docs/calibration.md).

/// The uncertainty the noisy recordings are read with: 2 % on each channel makes an FRF point
/// (a ratio of two channels) uncertain by 2 % x sqrt(2), in |H| and in phase (rad); the
/// damping and frequency are not compared where there are points.
inline const StatedUncertainty kStated{0.05, 0.002, 0.02 * std::sqrt(2.0)};

inline bench::CampaignConfig rigid_h0() {
    auto config =
        bench::load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper000-h0.toml");
    bench::apply_overrides(config, {"dampers.pd.model=rigid", "campaign.levels_g=[1.0, 2.0]"});
    return config;
}

struct Truth {
    double damping_ratio = 0.008;
    double modulus_pa = 69.0e9;
};

/// The rigid bench with the true values, predicted, 2 % noise on every channel.
inline std::filesystem::path measured_linear_bench(const std::string& name, const Truth& truth,
                                                   std::uint64_t noise_seed = 7) {
    auto config = rigid_h0();
    bench::apply_overrides(config,
                           {"structure.damping.default_ratio=" + exact_text(truth.damping_ratio),
                            "structure.beam.youngs_modulus_pa=" + exact_text(truth.modulus_pa)});
    const auto dir = fresh_dir(name);
    write_noisy_recording(predict(config, {}, 1), 0.02, noise_seed, dir);
    return dir;
}

inline std::vector<FreeParameter> linear_free(const bench::CampaignConfig& config) {
    return parse_free_parameters(config, {"structure.damping.default_ratio=0.002:0.02",
                                          "structure.beam.youngs_modulus_pa=60e9:80e9",
                                          "dampers.pd.contact.rolling_friction"});
}

inline const ParameterFinding& finding(const CalibrationResult& r, const std::string& path) {
    for (const auto& f : r.findings) {
        if (f.parameter.path == path) return f;
    }
    throw std::runtime_error("no finding for " + path);
}

}  // namespace sb::correlation::testing

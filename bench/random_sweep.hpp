// A sweep that is a random test (campaign.random): its starting drive from the linear
// model, the test run or resumed, and what the sweep returns (lines, spectra, settings).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "bench/campaign_plan.hpp"
#include "bench/campaign_spec.hpp"
#include "bench/coupled_specimen.hpp"
#include "bench/sweep_checkpoint.hpp"
#include "bench/sweep_runner.hpp"

namespace sb::bench {

struct RandomSweep {
    const RandomSpec* spec = nullptr;
    const SweepTask* task = nullptr;
    std::string arrangement;
    /// The control channel's band RMS to hold [m/s^2]; none: a fixed drive, the task's level
    /// the drive's RMS.
    std::optional<double> target_rms_m_s2;
    /// The linear model's control channel per unit drive at a frequency (its magnitude).
    std::function<double(double)> linear_gain;
};

/// The drive's RMS whose flat spectrum over the band gives `target_rms` through the linear
/// gain: sigma_a / sigma_F = sqrt(mean |H|^2 over the band).
double linear_start_drive_rms(const RandomSpec& spec, double target_rms,
                              const std::function<double(double)>& linear_gain);

/// Runs the sweep's random test from `checkpoint` (empty: from rest) and fills `out`: one
/// row per line of the band (status "random", or "closest" when the level did not hold),
/// random/<sweep>.csv's lines, the settings line, the periods run (half segments).
void run_random_sweep(CoupledSpecimen& specimen, const RandomSweep& sweep,
                      SweepCheckpoint& checkpoint, const std::function<void()>& save,
                      SweepProgress& progress, SweepResult& out);

}  // namespace sb::bench

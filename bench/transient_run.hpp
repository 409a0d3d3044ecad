// A run from rest (campaign.transient): the specimen driven at one frequency and a fixed
// amplitude for a set time, its channels recorded as time histories and as an envelope per
// period, checkpointed every few periods. Paper 004 runs its cantilever this way: the
// resonance builds up from rest, and a share of the granules is freed at 5 s.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/coupled_specimen.hpp"
#include "bench/specimen_plant.hpp"
#include "bench/sweep_checkpoint.hpp"

namespace sb::bench {

struct TransientDrive {
    double frequency_hz = 0.0;
    double amplitude = 0.0;  ///< the excitation's peak amplitude [N, m/s^2 or V]
    int periods = 0;         ///< whole periods to run
    int checkpoint_periods = 20;
};

/// Runs the periods `checkpoint` has not run yet, starting from rest when it has run none
/// (the structure deflected under the attachments' weight, at phase 0 of the drive).
/// Every `checkpoint_periods` periods the state and the rows so far go into `checkpoint` and
/// `save` is called; the specimen goes through state() and restore() there whether or not
/// the run was interrupted, so a resumed run repeats the same arithmetic. The rows are
/// SweepResult's transient_series and transient_envelope; `progress(periods_run)` follows
/// every checkpoint.
void run_transient(CoupledSpecimen& specimen, SpecimenPlant& plant, const TransientDrive& drive,
                   SweepCheckpoint& checkpoint, const std::function<void()>& save,
                   const std::function<void(int)>& progress);

/// The events a run's dampers have at set times: "pd: 9 of 30 particles freed at t = 5 s".
std::vector<std::string> release_events(const CampaignSpec& campaign);

/// Header rows of transient/<sweep>.csv and transient/<sweep>_envelope.csv.
std::string transient_series_header(const std::vector<std::string>& channels);
std::string transient_envelope_header(const std::vector<std::string>& channels);

}  // namespace sb::bench

// A characterisation run between two of its periods: what it has measured and the bed's
// state, enough to continue it exactly. A bed of tens of thousands of spheres runs for hours
// per grid point; its progress is saved as it goes, so an interrupted run resumes where it
// was and gives the numbers an uninterrupted one gives (docs/characterisation.md).
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "bench/attachment_types.hpp"
#include "dem/solver.hpp"

namespace sb::bench {

struct BedEnergy;

/// One period's measurements.
struct PeriodMeasurement {
    std::complex<double> q1, q2, q3;  ///< harmonics of the generalised force [N]
    double wall_work_j = 0.0;
    double stored_at_start_j = 0.0;  ///< the bed's mechanical energy at the period's start
    double kinetic_j = 0.0;          ///< mean over the period's samples
};

/// The samples every step of the bed's energy, and the ledger at every period's start
/// (EnclosureSetup::bed_energy).
struct EnergySamples {
    std::vector<double> kinetic_j;      ///< after each step
    std::vector<double> dissipated_j;   ///< cumulative, [0] before the first step
    std::vector<dem::EnergyLedger> at;  ///< [p]: at the start of period p

    /// Where the energy went over periods [begin, end) of n steps of dt each.
    [[nodiscard]] BedEnergy over(int begin, int end, int n, double dt) const;
};

/// A run after a whole number of periods.
struct RunProgress {
    int steps_per_period = 0;
    AttachmentState damper;      ///< the bed (DemDamper::state()) at the last period's end
    dem::EnergyLedger boundary;  ///< the solver's ledger there
    std::vector<PeriodMeasurement> periods;
    EnergySamples energy;  ///< with EnclosureSetup::bed_energy; else empty
};

/// Where a run saves its progress and which progress it continues.
struct RunCheckpoints {
    /// Continue this progress instead of starting from the settled bed (null: from the start).
    const RunProgress* resume = nullptr;
    /// Asked at every period's end that does not end the run: save now?
    std::function<bool()> due;
    std::function<void(const RunProgress&)> save;
};

/// Exact text (hexadecimal floats), sealed with a checksum as a sweep checkpoint is.
std::string serialize_run_progress(const RunProgress& progress);

/// Reads serialize_run_progress()'s text; damage (cut short, a changed byte, another format)
/// throws CheckpointError naming `file_name` and the line.
RunProgress parse_run_progress(const std::string& text, const std::string& file_name);

}  // namespace sb::bench

// Settings of the RMS amplitude controller (paper 000, section 3.2), with defaults and checks.
#pragma once

#include <limits>
#include <optional>

#include "core/violation.hpp"

namespace sb::control {

/// Options of AmplitudeController. Keys in validate() are the field names, which are also the
/// config keys. Amplitudes are in the plant's input unit (N for a force, m/s^2 for a base
/// acceleration); RMS levels in the control channel's unit.
struct ControllerOptions {
    /// Loose relative tolerance [-]: settling spread, two-period match, early-decision margin
    /// and acceptance band |rms - target| <= tolerance * target (paper 000: "large tolerance").
    double tolerance = 0.05;
    /// Values n that must stay within `tolerance` to call the response settled; a value is
    /// one period, or the mean of average_periods periods [periods].
    int window_periods = 4;
    /// Periods averaged into each value the window judges, as a swept-sine analyser averages
    /// [periods]. 1: every period is a value (paper 000). A damper that scatters from period
    /// to period (a chaotic single sphere) needs blocks: their means settle where single
    /// periods never do. window_periods, early_periods, limit_cycle_periods and
    /// closest_rerun_periods then count blocks; transient_periods and max_periods periods.
    int average_periods = 1;
    /// Fewest values in the window before an early too-low/too-high decision [periods]; at
    /// least 3 so that a monotonic drift can be told from scatter.
    int early_periods = 3;
    /// Periods skipped after every amplitude or frequency change before values enter the
    /// window (transient) [periods].
    int transient_periods = 1;
    /// Budget of periods per point before falling back to the closest amplitude [periods].
    int max_periods = 60;
    /// Periods re-run at the closest amplitude after a failure; those are recorded [periods].
    int closest_rerun_periods = 4;
    /// Amplitude of the first point (later points warm-start from the previous one); absent:
    /// the caller gives every sweep's start with AmplitudeController::set_start_amplitude().
    std::optional<double> initial_amplitude = 1.0;
    /// Lower bound of the amplitude (the amplitude is always > 0).
    double min_amplitude = 0.0;
    /// Upper bound of the amplitude (may be infinite).
    double max_amplitude = std::numeric_limits<double>::infinity();
    /// Largest factor by which one update may raise or lower the amplitude [-].
    double max_step_factor = 2.0;
    /// Widening o of the stored bracket levels, (1 -/+ o * tolerance) * rms [-] (HFelem
    /// `overshoot`): makes the secant a "loosened gradient" that tolerates scatter.
    double overshoot = 1.0;
    /// A two-period limit cycle needs consecutive values apart by at least
    /// limit_cycle_jump * tolerance (relative) [-].
    double limit_cycle_jump = 2.0;
    /// Periods that must alternate to recognise a two-period limit cycle (even, >= 4, i.e.
    /// at least two repetitions on each side; random scatter rarely passes three) [periods].
    int limit_cycle_periods = 6;
    /// Bracket restarts (secant stalls) after which only the ratio rule is used [-].
    int max_restarts = 5;
    /// Periods over which a monotone drift in the window is assumed to go on at most: a
    /// window within the tolerance is settled only if its drift, extrapolated as a geometric
    /// decay (or linearly when it does not decay) over at most this many periods, stays
    /// within half the tolerance. The default is the e-folding time 1/(2 pi zeta) of a
    /// 0.5 %-damped mode at resonance, paper 000's empty beam; 0: no drift test [periods].
    int drift_horizon_periods = 32;
    /// A window is settled only when the control channel's complex fundamental (the plant's
    /// harmonics[0]) agrees over it too, within the tolerance: a beating transient turns the
    /// phasor while the RMS may stay within the tolerance.
    bool phase_test = true;

    /// Every violated constraint, keys as above.
    [[nodiscard]] Violations validate() const;
};

}  // namespace sb::control

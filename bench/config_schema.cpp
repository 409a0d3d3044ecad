// The keys of [campaign], [arrangements.NAME], [controller] and [output], and the checks that
// tie the tables together (points and arrangements that must exist).
#include "bench/config_schema.hpp"

#include <algorithm>

#include "bench/campaign_config.hpp"
#include "bench/channels.hpp"
#include "bench/schema_parts.hpp"
#include "config/builder.hpp"

namespace sb::bench {
namespace {

using config::Bound;
using config::TableBuilder;

std::shared_ptr<const config::Table> frequencies_table() {
    TableBuilder<FrequencyGridSpec> t(
        "the frequency grid",
        "The grid of every sweep: given, or built around the first mode (of the structure with "
        "the particles as rigid mass) equally spaced in the phase angle atan(2 zeta r/(1 - r^2)) "
        "of a single mode with `grid_damping_ratio`, so that the points crowd near resonance "
        "where half-power and circle fits need them.");
    t.numbers(
         "values_hz", [](FrequencyGridSpec & g) -> auto& { return g.values_hz; },
         "explicit frequency grid")
        .unit("Hz")
        .bound(Bound::positive())
        .doc("explicit frequency grid; when given the keys below but `direction` are not used");
    const auto built = [](const FrequencyGridSpec& g) { return g.values_hz.empty(); };
    t.number(
         "low_ratio", [](FrequencyGridSpec & g) -> auto& { return g.low_ratio; },
         "lowest frequency / first mode")
        .unit("-")
        .bound(Bound::positive())
        .when(built, "not used with values_hz", true);
    t.number(
         "high_ratio", [](FrequencyGridSpec & g) -> auto& { return g.high_ratio; },
         "highest frequency / first mode (above low_ratio)")
        .unit("-")
        .bound(Bound::positive())
        .when(built, "not used with values_hz", true);
    t.integer(
         "count", [](FrequencyGridSpec & g) -> auto& { return g.count; },
         "points of the built grid")
        .bound(Bound::at_least(2))
        .when(built, "not used with values_hz", true);
    t.number(
         "grid_damping_ratio", [](FrequencyGridSpec & g) -> auto& { return g.grid_damping_ratio; },
         "damping that places the built grid")
        .unit("-")
        .bound(Bound::closed(1e-4, 0.5))
        .when(built, "not used with values_hz", true);
    t.choice(
        "direction", [](FrequencyGridSpec & g) -> auto& { return g.direction; },
        FrequencyGridSpec::kDirectionNames, "sweep direction");
    t.integer(
         "refine_points", [](FrequencyGridSpec & g) -> auto& { return g.refine_points; },
         "most frequencies a sweep adds near its peak to resolve its estimates")
        .bound(Bound::non_negative())
        .doc(
            "most frequencies a sweep on the grid adds near its peak when its half-power or "
            "circle-fit estimate is not resolved (peak at an edge, no half-power crossing, too "
            "few points in the band): a lab engineer's refinement, deterministic and "
            "resumable; a sweep that spends them says so. 0: none");
    t.check([](const FrequencyGridSpec& g) { return g.validate(); });
    return t.build();
}

std::shared_ptr<const config::Table> drive_table() {
    TableBuilder<DriveSpec> t(
        "the drive",
        "How each point's drive amplitude is set: by the RMS controller to `campaign.levels_g` "
        "at the control point (paper 000), or fixed per sweep as in an open-loop test (a "
        "signal generator at a set voltage, an eccentric of set throw: papers 002 and 004). A "
        "fixed point runs until the control channel is steady by the controller's settling "
        "test (`[controller]` tolerance, window, drift and phase tests, transient and "
        "max_periods), else it is recorded as `unsettled` with the mean of its later half.");
    t.choice(
         "kind", [](DriveSpec & d) -> auto& { return d.kind; }, DriveSpec::kKindNames,
         "controlled RMS level or fixed amplitude")
        .doc(
            "`controlled`: the RMS controller holds `campaign.levels_g` at the control point; "
            "`fixed`: each of `amplitudes` is a sweep's level, driven unchanged at every "
            "frequency (no controller); points.csv's `level_g` column then holds the "
            "amplitude, in its own unit");
    const auto fixed = [](const DriveSpec& d) { return d.fixed(); };
    t.choice(
         "quantity", [](DriveSpec & d) -> auto& { return d.quantity; }, DriveSpec::kQuantityNames,
         "what a fixed amplitude is")
        .doc(
            "`excitation`: the excitation's own input, a force [N], a base acceleration "
            "[m/s^2], or through `[physics.shaker]` the coil voltage [V]; `base-displacement`: "
            "under base excitation the base displacement [m], its acceleration (2 pi f)^2 X "
            "growing along the sweep (an eccentric exciter)")
        .when(fixed, "used with kind = \"fixed\"", true);
    t.numbers(
         "amplitudes", [](DriveSpec & d) -> auto& { return d.amplitudes; },
         "peak amplitudes of a fixed drive, one sweep each")
        .unit("N, m/s^2, V or m")
        .bound(Bound::positive())
        .doc(
            "peak amplitudes of a fixed drive, one sweep each, in the unit of `quantity`; "
            "`kind = \"fixed\"` needs at least one and then takes no `campaign.levels_g`");
    return t.build();
}

std::shared_ptr<const config::Table> transient_table() {
    TableBuilder<TransientSpec> t(
        "a run from rest",
        "Instead of stepped sines, each sweep (arrangement x `campaign.drive.amplitudes`) "
        "drives the specimen at one frequency for a set time from rest and records every "
        "channel's time history and its envelope per period (transient/ in the recording "
        "directory). Needs `campaign.drive.kind = \"fixed\"`; `[campaign.frequencies]` is "
        "not used. Events at set times (a lock's release) come at the same moment of a resumed "
        "run.");
    t.number(
         "duration_s", [](TransientSpec & s) -> auto& { return s.duration_s; },
         "simulated time of each run; 0: a stepped-sine campaign")
        .unit("s")
        .bound(Bound::non_negative());
    t.number(
         "frequency_hz", [](TransientSpec & s) -> auto& { return s.frequency_hz; },
         "drive frequency")
        .unit("Hz")
        .bound(Bound::positive())
        .doc("drive frequency (required with duration_s > 0)");
    t.integer(
         "checkpoint_periods", [](TransientSpec & s) -> auto& { return s.checkpoint_periods; },
         "periods between checkpoints (an interrupted run resumes from the last)")
        .bound(Bound::at_least(1));
    return t.build();
}

std::shared_ptr<const config::Table> random_table() {
    TableBuilder<RandomSpec> t(
        "a random test",
        "Instead of stepped sines, each sweep (arrangement x level) drives the specimen with "
        "band-limited Gaussian noise between `low_hz` and `high_hz`, as a random test's "
        "analyser does: the drive's RMS is adjusted segment by segment until the control "
        "channel's RMS in the band holds `campaign.levels_g` (a fixed drive: "
        "`campaign.drive.amplitudes` are RMS forces), then `averages` Hann-windowed segments "
        "overlapping by half give H1 = G_xy / G_xx and the coherence at every line of the "
        "band. points.csv then holds one row per line (status `random`, the reference's "
        "amplitude 1, each channel's H1) and damping.csv the estimators on it. Needs a force "
        "excitation without `[physics.shaker]`; `[campaign.frequencies]` is not used.");
    t.number(
         "low_hz", [](RandomSpec & s) -> auto& { return s.low_hz; },
         "lower edge of the drive and analysis band")
        .unit("Hz")
        .bound(Bound::non_negative());
    t.number(
         "high_hz", [](RandomSpec & s) -> auto& { return s.high_hz; },
         "upper edge of the band; 0: a stepped-sine campaign")
        .unit("Hz")
        .bound(Bound::non_negative());
    t.number(
         "resolution_hz", [](RandomSpec & s) -> auto& { return s.resolution_hz; },
         "line spacing of the spectra")
        .unit("Hz")
        .bound(Bound::positive())
        .doc(
            "line spacing of the spectra; each segment lasts 1 / resolution_hz. A twentieth of "
            "the half-power bandwidth 2 zeta f_n or finer keeps the damping identified within "
            "about 1 % (docs/campaign.md, random tests)");
    t.integer(
         "averages", [](RandomSpec & s) -> auto& { return s.averages; },
         "Hann-windowed segments averaged, overlapping by half")
        .bound(Bound::at_least(1));
    t.integer(
         "level_blocks", [](RandomSpec & s) -> auto& { return s.level_blocks; },
         "most segments run to bring the level in before the averaging")
        .bound(Bound::at_least(1))
        .doc(
            "most segments run to bring the level in before the averaging (the first also lets "
            "the start from rest die out); a level still off by more than `tolerance` over "
            "the averaging marks the sweep's lines `closest`");
    t.number(
         "tolerance", [](RandomSpec & s) -> auto& { return s.tolerance; },
         "relative error of the band RMS at which the level holds")
        .bound(Bound::positive());
    t.integer(
         "checkpoint_segments", [](RandomSpec & s) -> auto& { return s.checkpoint_segments; },
         "half segments of the averaging between checkpoints (an interrupted test resumes "
         "from the last; every level segment is one)")
        .bound(Bound::at_least(1));
    return t.build();
}

std::shared_ptr<const config::Table> channel_table() {
    TableBuilder<ChannelSpec> t(
        "a further recorded channel",
        "A channel recorded besides the control and response accelerations: a named point's "
        "acceleration, velocity or displacement along any direction (absolute under base "
        "excitation), or the force a damper applies to the structure. Repeat the table for "
        "each channel.");
    t.string(
         "name", [](ChannelSpec & c) -> auto& { return c.name; }, "channel name")
        .optional()
        .doc(
            "column name in points.csv and series/; absent: the quantity's prefix (`acc`, "
            "`vel`, `disp`, `force`), the point or damper and, off the excitation direction, "
            "its axis (`acc_bracket_y`; `_dir` for a direction along no axis)");
    t.choice(
        "quantity", [](ChannelSpec & c) -> auto& { return c.quantity; },
        ChannelSpec::kQuantityNames, "what the channel reads (m/s^2, m/s, m or N)");
    t.string(
         "point", [](ChannelSpec & c) -> auto& { return c.point; }, "named point read")
        .optional()
        .doc("named point whose motion is read (required for a motion quantity)");
    t.string(
         "damper", [](ChannelSpec & c) -> auto& { return c.damper; },
         "the damper whose force on the structure is read")
        .optional()
        .doc(
            "the `[dampers.NAME]` whose force on the structure is read (required with "
            "`quantity = \"damper-force\"`; not a rigid damper, whose mass is part of the "
            "structure)");
    t.vector3(
         "direction", [](ChannelSpec & c) -> auto& { return c.direction; },
         "direction of the reading (normalised)")
        .doc("direction of the reading, not all 0 (normalised); absent: the excitation direction");
    return t.build();
}

std::shared_ptr<const config::Table> campaign_table() {
    TableBuilder<CampaignConfig> t("the campaign");
    t.string(
        "name", [](CampaignConfig & c) -> auto& { return c.name; },
        "campaign name, used in output file names");
    t.string(
        "description", [](CampaignConfig & c) -> auto& { return c.description; }, "free text");
    t.numbers(
         "levels_g", [](CampaignConfig & c) -> auto& { return c.campaign.levels_g; },
         "target RMS levels at the control point")
        .unit("g")
        .bound(Bound::positive())
        .doc(
            "target RMS accelerations at the control point (9.80665 m/s^2 per g); a controlled "
            "drive needs at least one (a fixed drive takes `campaign.drive.amplitudes`)");
    t.strings(
         "arrangements",
         [](CampaignConfig & c) -> auto& { return c.campaign.arrangement_selection; },
         "arrangements to run")
        .doc("which `[arrangements.NAME]` to run, in this order; empty: every one defined");
    t.string(
         "control_point", [](CampaignConfig & c) -> auto& { return c.campaign.control_point; },
         "named point whose RMS acceleration is controlled")
        .doc(
            "named point whose RMS acceleration along the excitation direction is controlled "
            "(channel `acc_<point>`)");
    t.strings(
        "response_points", [](CampaignConfig & c) -> auto& { return c.campaign.response_points; },
        "named points recorded besides the control point (channels `acc_<point>`, along the "
        "excitation direction)");
    t.array_of_tables(
        "channels", [](CampaignConfig & c) -> auto& { return c.campaign.channels; },
        channel_table());
    t.choice(
         "point_start", [](CampaignConfig & c) -> auto& { return c.campaign.point_start; },
         CampaignSpec::kPointStartNames, "how the structure starts each point after the first")
        .doc(
            "how the structure starts each point after the first of a sweep (the first starts "
            "from the linear steady state of the structure with the particles as rigid mass, "
            "the particles from their settled bed; later points always keep the particles' "
            "state): where the previous point left it; the linear steady state scaled in "
            "amplitude and phase to the response of the previous point's equivalent driven "
            "mode; or the plain linear steady state at the new frequency and start amplitude, "
            "exact for a linear specimen but far from a particle-damped beam's response near "
            "resonance. See docs/campaign.md for what each costs");
    t.boolean(
         "scale_response_on_update",
         [](CampaignConfig & c) -> auto& { return c.campaign.scale_response_on_update; },
         "scale the structure's response with every amplitude update")
        .doc(
            "at every amplitude update within a point, scale the structure's response by "
            "new/old amplitude about its mean over the last period (the particles ride with "
            "their enclosures): the update lands on the new steady state of a linear structure "
            "instead of starting a slow transient; see docs/campaign.md");
    t.integer(
         "seed", [](CampaignConfig & c) -> auto& { return c.campaign.seed; },
         "seed of the particle filling")
        .bound(Bound::non_negative());
    t.integer(
         "seeds", [](CampaignConfig & c) -> auto& { return c.campaign.seeds; },
         "fillings of the bed per sweep (seeds seed, seed + 1, ...)")
        .bound(Bound::at_least(1))
        .doc(
            "fillings of the bed per sweep (seeds `seed`, `seed` + 1, ...): each its own FRF "
            "and estimates; damping.csv gives their mean and scatter per level, "
            "damping_fillings.csv each one");
    t.table(
        "frequencies", [](CampaignConfig & c) -> auto& { return c.campaign.frequencies; },
        frequencies_table());
    t.table(
        "drive", [](CampaignConfig & c) -> auto& { return c.campaign.drive; }, drive_table());
    t.table(
        "transient", [](CampaignConfig & c) -> auto& { return c.campaign.transient; },
        transient_table());
    t.table(
        "random", [](CampaignConfig & c) -> auto& { return c.campaign.random; }, random_table());
    return t.build();
}

std::shared_ptr<const config::Table> arrangement_table() {
    TableBuilder<ArrangementSpec> t(
        "a mounting of the specimen",
        "How the specimen is mounted for a series of sweeps (paper 000, Figs. 1-2). The shaker "
        "drives z. Horizontal: the section's long side (y) is vertical, gravity along -y. "
        "Vertical: gravity along -z. The damper axis is tilted from z towards +y about the beam "
        "axis x by the angle.");
    t.choice(
        "oscillation", [](ArrangementSpec & a) -> auto& { return a.oscillation; },
        ArrangementSpec::kOscillationNames, "direction of the beam's motion");
    t.number(
         "damper_angle_deg", [](ArrangementSpec & a) -> auto& { return a.damper_angle_deg; },
         "angle between the damper axis and the motion")
        .unit("deg")
        .bound(Bound::closed(0.0, 90.0));
    t.number(
         "block_mass_kg", [](ArrangementSpec & a) -> auto& { return a.block_mass_kg; },
         "mounting block added at each damper point")
        .unit("kg")
        .bound(Bound::non_negative())
        .doc(
            "mounting block added at each damper point (paper 000: 31 g at 45 deg), a point "
            "mass at the block's centre of gravity");
    t.number(
         "block_cathetus_m", [](ArrangementSpec & a) -> auto& { return a.block_cathetus_m; },
         "cathetus of the 45-degree mounting wedge")
        .unit("m")
        .bound(Bound::non_negative())
        .doc(
            "the block is a right isosceles wedge with this cathetus, lying on one cathetus "
            "across y with the enclosure standing on its hypotenuse; it raises the enclosure's "
            "mounting face by half the cathetus (paper 000 Table 1: 20 mm). Needs "
            "`damper_angle_deg = 45`");
    t.number(
         "gravity_tilt_deg", [](ArrangementSpec & a) -> auto& { return a.gravity_tilt_deg; },
         "misalignment of the mount: gravity turned about the beam axis x by this angle "
         "(right-handed; horizontal oscillation: g sin(angle) along -z, the motion)")
        .unit("deg")
        .bound(Bound::closed(-45.0, 45.0))
        .calibrated_within(-10.0, 10.0);
    t.vector3(
         "mount_lift_m", [](ArrangementSpec & a) -> auto& { return a.mount_lift_m; },
         "further displacement of the enclosure's mounting face (a spacer, a side mount), "
         "structure frame")
        .unit("m");
    t.check([](const ArrangementSpec& a) { return a.validate(); });
    return t.build();
}

std::shared_ptr<const config::Table> controller_table() {
    using control::ControllerOptions;
    TableBuilder<ControllerOptions> t("the RMS amplitude controller",
                                      "The RMS amplitude controller of paper 000 section 3.2 "
                                      "(see docs/control.md).");
    t.number(
         "tolerance", [](ControllerOptions & c) -> auto& { return c.tolerance; },
         "relative RMS tolerance")
        .unit("-")
        .bound(Bound::closed(1e-6, 0.5));
    t.integer(
         "window_periods", [](ControllerOptions & c) -> auto& { return c.window_periods; },
         "periods (or averages, with average_periods) that must stay within the tolerance")
        .bound(Bound::at_least(3));
    t.integer(
         "average_periods", [](ControllerOptions & c) -> auto& { return c.average_periods; },
         "periods averaged into each value the window judges")
        .bound(Bound::at_least(1))
        .doc(
            "as a swept-sine analyser averages: each value of the window is the mean RMS and "
            "mean fundamental of this many periods. 1 (paper 000): every period is a value. A "
            "damper whose response scatters from period to period (one sphere bouncing "
            "chaotically in its gap, paper 003) never holds a window of single periods within "
            "the tolerance; the means of blocks settle. window_periods, early_periods, "
            "limit_cycle_periods and closest_rerun_periods then count blocks, "
            "transient_periods, max_periods and drift_horizon_periods periods");
    t.integer(
         "early_periods", [](ControllerOptions & c) -> auto& { return c.early_periods; },
         "values needed for an early too-low/too-high decision (at most window_periods)")
        .bound(Bound::at_least(3));
    t.integer(
         "transient_periods", [](ControllerOptions & c) -> auto& { return c.transient_periods; },
         "periods skipped after every change")
        .bound(Bound::non_negative());
    t.integer(
         "max_periods", [](ControllerOptions & c) -> auto& { return c.max_periods; },
         "budget per point before falling back to the closest amplitude")
        .bound(Bound::at_least(1));
    t.integer(
         "closest_rerun_periods",
         [](ControllerOptions & c) -> auto& { return c.closest_rerun_periods; },
         "periods re-run at the closest amplitude")
        .bound(Bound::at_least(1));
    t.number(
         "initial_amplitude", [](ControllerOptions & c) -> auto& { return c.initial_amplitude; },
         "first amplitude of every sweep")
        .unit("N, or m/s^2 for base excitation")
        .bound(Bound::positive())
        .automatic("from the linear model with the particles as rigid mass");
    t.number(
         "min_amplitude", [](ControllerOptions & c) -> auto& { return c.min_amplitude; },
         "lower amplitude bound")
        .unit("N, or m/s^2")
        .bound(Bound::non_negative());
    t.number(
         "max_amplitude", [](ControllerOptions & c) -> auto& { return c.max_amplitude; },
         "upper amplitude bound (above min_amplitude)")
        .unit("N, or m/s^2")
        .bound(Bound::positive().allow_infinite());
    t.number(
         "max_step_factor", [](ControllerOptions & c) -> auto& { return c.max_step_factor; },
         "largest factor of one update")
        .unit("-")
        .bound(Bound::greater_than(1.0));
    t.number(
         "overshoot", [](ControllerOptions & c) -> auto& { return c.overshoot; },
         "bracket widening (loosened gradient); overshoot * tolerance < 0.5")
        .unit("-")
        .bound(Bound::non_negative());
    t.number(
         "limit_cycle_jump", [](ControllerOptions & c) -> auto& { return c.limit_cycle_jump; },
         "two-period limit cycle: jump / tolerance")
        .unit("-")
        .bound(Bound::at_least(1.0));
    t.integer(
         "limit_cycle_periods",
         [](ControllerOptions & c) -> auto& { return c.limit_cycle_periods; },
         "alternating periods of a limit cycle (even)")
        .bound(Bound::at_least(4));
    t.integer(
         "max_restarts", [](ControllerOptions & c) -> auto& { return c.max_restarts; },
         "secant restarts before only the ratio rule is used")
        .bound(Bound::non_negative());
    t.integer(
         "drift_horizon_periods",
         [](ControllerOptions & c) -> auto& { return c.drift_horizon_periods; },
         "periods a drift in the window is extrapolated over")
        .bound(Bound::non_negative())
        .doc(
            "a window within the tolerance is settled only if its monotone drift, extrapolated "
            "as a geometric decay (linearly when it does not decay) over at most this many "
            "periods, stays within half the tolerance; 32 is the e-folding time of a "
            "0.5 %-damped mode; 0 turns the test off");
    t.boolean(
        "phase_test", [](ControllerOptions & c) -> auto& { return c.phase_test; },
        "a window is settled only when the control channel's complex fundamental agrees "
        "over it within the tolerance too (a beating transient turns it while the RMS may "
        "not move)");
    t.check([](const ControllerOptions& c) { return c.validate(); });
    return t.build();
}

std::shared_ptr<const config::Table> output_table() {
    TableBuilder<OutputSpec> t("what the campaign writes");
    t.boolean(
        "series", [](OutputSpec & o) -> auto& { return o.series; },
        "time histories of every steady window in series/");
    t.integer(
         "series_samples_per_period",
         [](OutputSpec & o) -> auto& { return o.series_samples_per_period; },
         "samples per period in those")
        .bound(Bound::at_least(8));
    t.boolean(
        "uff", [](OutputSpec & o) -> auto& { return o.uff; },
        "transfer functions as UFF58 (frf.uff)");
    t.boolean(
        "plots", [](OutputSpec & o) -> auto& { return o.plots; },
        "SVG plots through gnuplot, when it is installed");
    t.boolean(
        "energy", [](OutputSpec & o) -> auto& { return o.energy; },
        "energy.csv: per point, DEM damper and filling, the energy per period over the steady "
        "window: wall work, dissipation by normal damping, friction and rolling, kinetic "
        "energy, dissipation per horizontal layer and each layer's agitation (its particles' "
        "mean kinetic energy relative to the enclosure); for characterize, as --energy");
    t.integer(
         "energy_layers", [](OutputSpec & o) -> auto& { return o.energy_layers; },
         "horizontal layers (along gravity) of energy.csv and of characterize --energy")
        .bound(Bound::at_least(1))
        .when([](const OutputSpec& o) { return o.energy; }, "only with energy = true", true);
    t.choice(
         "vtk", [](OutputSpec & o) -> auto& { return o.vtk; }, OutputSpec::kVtkNames,
         "ParaView files of the beds in vtk/")
        .doc(
            "ParaView (legacy VTK) files of every DEM bed in its enclosure frame at the end of "
            "a point's steady window, in `vtk/`: `resonance` at the point of largest response "
            "of each sweep, `all` at every point");
    return t.build();
}

std::shared_ptr<const config::Table> air_drag_table() {
    TableBuilder<AirDragSpec> t(
        "aerodynamic drag of the beam",
        "Quadratic air drag of a thin beam moving across its wide face, f = -1/2 rho C_D b |v| v "
        "per unit length along the face normal (z), lumped at the midpoints of `stations` equal "
        "strips of the beam; damping that grows in proportion to the amplitude. Beam "
        "structures only.");
    t.number(
         "drag_coefficient", [](AirDragSpec & a) -> auto& { return a.drag_coefficient; },
         "drag coefficient C_D of the section across its wide face; 0 turns the drag off")
        .unit("-")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 60.0)
        .doc(
            "drag coefficient C_D of the section across its wide face (about 2 for a flat "
            "plate broadside to the flow; an oscillating strip's is larger at small "
            "Keulegan-Carpenter numbers); 0 turns the drag off");
    t.number(
         "air_density_kg_m3", [](AirDragSpec & a) -> auto& { return a.air_density_kg_m3; },
         "density of the surrounding air")
        .unit("kg/m^3")
        .bound(Bound::positive());
    t.integer(
         "stations", [](AirDragSpec & a) -> auto& { return a.stations; },
         "equal strips of the beam the drag is lumped over, one point at each strip's middle")
        .bound(Bound::at_least(1));
    return t.build();
}

std::shared_ptr<const config::Table> microslip_table() {
    TableBuilder<MicroslipSpec> t(
        "microslip in a joint",
        "Microslip in a joint or clamp as a power-law dashpot at a named point, along the "
        "excitation direction: f = -c (|v| / v_ref)^chi v. Its equivalent damping grows like "
        "the amplitude to the power chi (Iwan-type microslip: 0 < chi < 1).");
    const auto on = [](const MicroslipSpec& m) { return m.on(); };
    t.string(
        "point", [](MicroslipSpec & m) -> auto& { return m.point; },
        "named point of the joint (required when damping_n_s_per_m > 0)");
    t.number(
         "damping_n_s_per_m", [](MicroslipSpec & m) -> auto& { return m.damping_n_s_per_m; },
         "dashpot coefficient c at the reference velocity; 0 turns the microslip off")
        .unit("N s/m")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 20.0);
    t.number(
         "exponent", [](MicroslipSpec & m) -> auto& { return m.exponent; },
         "power chi of the velocity ratio: damping grows like the amplitude^chi")
        .unit("-")
        .bound(Bound::closed(0.0, 2.0))
        .calibrated_within(0.0, 1.5)
        .when(on, "only with damping_n_s_per_m > 0");
    t.number(
         "reference_velocity_m_s",
         [](MicroslipSpec & m) -> auto& { return m.reference_velocity_m_s; },
         "velocity at which the dashpot's coefficient is c")
        .unit("m/s")
        .bound(Bound::positive())
        .when(on, "only with damping_n_s_per_m > 0");
    return t.build();
}

std::shared_ptr<const config::Table> cubic_spring_table() {
    TableBuilder<CubicSpringSpec> t(
        "a hardening cubic spring",
        "A cubic spring from a named point to the fixed frame, along the excitation direction: "
        "f = -k3 u^3, u the point's displacement from rest. It stands in for the geometric "
        "stiffening of the driven mode: the frequency rises with the square of the amplitude.");
    t.string(
        "point", [](CubicSpringSpec & c) -> auto& { return c.point; },
        "named point of the spring (required when stiffness_n_per_m3 > 0)");
    t.number(
         "stiffness_n_per_m3", [](CubicSpringSpec & c) -> auto& { return c.stiffness_n_per_m3; },
         "cubic stiffness k3; 0 turns the spring off")
        .unit("N/m^3")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1e5);
    return t.build();
}

std::shared_ptr<const config::Table> iwan_joint_table() {
    TableBuilder<IwanJointSpec> t(
        "a joint's microslip and macroslip (Iwan)",
        "A joint at a named point that the linear model holds stuck, as a discrete Iwan "
        "element along the excitation direction: parallel springs with Coulomb sliders whose "
        "slip displacements follow Segalman's density phi^chi up to phi_max (slip force "
        "F_S = K_T phi_max (1 + chi) / (2 + chi)). It adds only what slip takes away from the "
        "stuck stiffness: damping that grows like the amplitude^(1 + chi) below macroslip, and "
        "a slight softening.");
    const auto on = [](const IwanJointSpec& j) { return j.on(); };
    t.string(
        "point", [](IwanJointSpec & j) -> auto& { return j.point; },
        "named point of the joint (required when stiffness_n_per_m > 0)");
    t.number(
         "stiffness_n_per_m", [](IwanJointSpec & j) -> auto& { return j.stiffness_n_per_m; },
         "stiffness K_T of the stuck joint, part of the linear model already (it sets how much "
         "slip can take away, not the model's stiffness); 0 turns the joint off")
        .unit("N/m")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1e7);
    t.number(
         "macroslip_displacement_m",
         [](IwanJointSpec & j) -> auto& { return j.macroslip_displacement_m; },
         "displacement phi_max beyond which the joint's last slider moves: the whole joint "
         "slides")
        .unit("m")
        .bound(Bound::positive())
        .calibrated_within(1e-7, 1.0)
        .when(on, "only with stiffness_n_per_m > 0");
    t.number(
         "exponent", [](IwanJointSpec & j) -> auto& { return j.exponent; },
         "chi of the slip density: the damping grows like the amplitude^(1 + chi) below "
         "macroslip (about -0.5 for bolted lap joints)")
        .unit("-")
        .bound(Bound::open(-1.0, 1.0))
        .calibrated_within(-0.9, 0.0)
        .when(on, "only with stiffness_n_per_m > 0");
    t.integer(
         "elements", [](IwanJointSpec & j) -> auto& { return j.elements; },
         "Jenkins elements the density is cut into (geometric bins from 1e-4 phi_max; 96 are "
         "within 0.6 % of 8000)")
        .bound(Bound::at_least(2))
        .when(on, "only with stiffness_n_per_m > 0");
    return t.build();
}

std::shared_ptr<const config::Table> shaker_table() {
    TableBuilder<ShakerSpec> t(
        "the electrodynamic shaker",
        "The shaker between the amplifier and the drive point of a force-excited structure, "
        "joined to it by a rigid stinger: the voltage V drives the coil (L di/dt + R i = V - "
        "Bl v), the force factor Bl turns its current into force, the armature rides on its "
        "suspension. On, the controller sets the amplifier's voltage, the recording's "
        "reference channel `voltage` holds it and a response channel `force` the force into "
        "the structure (a force transducer at the stinger's end). The back-EMF damps the "
        "voltage-referenced FRF (about Bl^2 / R at the drive point), not the force-referenced "
        "one.");
    const auto on = [](const ShakerSpec& s) { return s.on(); };
    const char* only = "only with force_factor_n_per_a > 0";
    t.number(
         "force_factor_n_per_a", [](ShakerSpec & s) -> auto& { return s.force_factor_n_per_a; },
         "force factor Bl of the coil in the magnet's field; 0 leaves the shaker out (the drive "
         "is an ideal force)")
        .unit("N/A")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1000.0);
    t.number(
         "coil_resistance_ohm", [](ShakerSpec & s) -> auto& { return s.coil_resistance_ohm; },
         "resistance R of the coil with the amplifier's output resistance (a voltage-mode "
         "amplifier: small)")
        .unit("ohm")
        .bound(Bound::positive())
        .calibrated_within(0.01, 100.0)
        .when(on, only);
    t.number(
         "coil_inductance_h", [](ShakerSpec & s) -> auto& { return s.coil_inductance_h; },
         "inductance L of the coil: the current lags the voltage by atan(w L / R)")
        .unit("H")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 0.1)
        .when(on, only);
    t.number(
         "armature_mass_kg", [](ShakerSpec & s) -> auto& { return s.armature_mass_kg; },
         "moving mass of the armature, its table and the stinger, added to the structure at "
         "the drive point (on an imported model: to the point's translation DOFs)")
        .unit("kg")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 10.0)
        .when(on, only);
    t.number(
         "suspension_stiffness_n_per_m",
         [](ShakerSpec & s) -> auto& { return s.suspension_stiffness_n_per_m; },
         "stiffness k_s of the armature's suspension (flexures)")
        .unit("N/m")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1e6)
        .when(on, only);
    t.number(
         "suspension_damping_n_s_per_m",
         [](ShakerSpec & s) -> auto& { return s.suspension_damping_n_s_per_m; },
         "mechanical damping c_s of the armature's suspension")
        .unit("N s/m")
        .bound(Bound::non_negative())
        .calibrated_within(0.0, 1000.0)
        .when(on, only);
    return t.build();
}

std::shared_ptr<const config::Table> physics_table() {
    TableBuilder<PhysicsSpec> t(
        "physics a model may leave out",
        "Optional components of the structure and its rig, each off by default, that a "
        "diagnosis switches on and fits (docs/diagnosis.md, the physics catalogue).");
    t.table(
        "air_drag", [](PhysicsSpec & p) -> auto& { return p.air_drag; }, air_drag_table());
    t.table(
        "microslip", [](PhysicsSpec & p) -> auto& { return p.microslip; }, microslip_table());
    t.table(
        "cubic_spring", [](PhysicsSpec & p) -> auto& { return p.cubic_spring; },
        cubic_spring_table());
    t.table(
        "iwan_joint", [](PhysicsSpec & p) -> auto& { return p.iwan_joint; }, iwan_joint_table());
    t.table(
        "shaker", [](PhysicsSpec & p) -> auto& { return p.shaker; }, shaker_table());
    return t.build();
}

/// Names a structure of this spec offers as points (beam: points, masses and supports;
/// lumped: masses; matrix: the prefixes of named DOFs).
std::vector<std::string> point_names(const structure::StructureSpec& spec) {
    std::vector<std::string> names;
    switch (spec.kind) {
        case structure::StructureSpec::Kind::beam:
            for (const auto& p : spec.beam.points) names.push_back(p.name);
            for (const auto& m : spec.beam.resolved().masses) names.push_back(m.name);
            for (const auto& s : spec.beam.supports) names.push_back(s.name);
            break;
        case structure::StructureSpec::Kind::lumped:
            for (const auto& m : spec.lumped.masses) names.push_back(m.name);
            break;
        case structure::StructureSpec::Kind::matrix:
            for (const auto& [dof, row] : spec.matrix.named_dofs) {
                names.push_back(structure::MatrixSpec::point_of(dof));
            }
            break;
    }
    return names;
}

/// [[campaign.channels]]: what each reads exists, and every channel name is unique among
/// the recording's channels.
template <class Known>
void check_channels(const CampaignConfig& config, const Known& known, Violations& out) {
    using Q = ChannelSpec::Quantity;
    const auto text = [](const std::string& s) { return config::quoted(s); };
    const auto& campaign = config.campaign;
    std::vector<std::string> taken{"force", "voltage", "base_acc"};
    CampaignSpec accelerations = campaign;  // the control and response channels alone
    accelerations.channels.clear();
    for (const auto& c : recorded_channels(accelerations, config.structure.excitation)) {
        taken.push_back(c.name);
    }
    for (std::size_t i = 0; i < campaign.channels.size(); ++i) {
        const ChannelSpec& c = campaign.channels[i];
        const std::string key = config::index_path("campaign.channels", i);
        if (c.quantity == Q::damper_force) {
            const auto damper =
                std::find_if(campaign.dampers.begin(), campaign.dampers.end(),
                             [&](const DamperSpec& d) { return d.name == c.damper; });
            if (c.damper.empty()) {
                out.push_back({key + ".damper", "absent",
                               "is required with quantity = \"damper-force\"", ""});
            } else if (damper == campaign.dampers.end()) {
                out.push_back({key + ".damper", text(c.damper),
                               "must name a table [dampers." + c.damper + "]", ""});
            } else if (damper->model == DamperSpec::Model::rigid) {
                out.push_back({key + ".damper", text(c.damper),
                               "names a rigid damper, whose mass is part of the structure: it "
                               "applies no force of its own",
                               ""});
            }
        } else if (c.point.empty()) {
            out.push_back({key + ".point", "absent", "is required for a motion channel", ""});
        } else if (!known(c.point)) {
            out.push_back(
                {key + ".point", text(c.point), "must name a point of the structure", ""});
        }
        if (c.direction && !(c.direction->norm() > 0.0)) {
            out.push_back({key + ".direction", "[0, 0, 0]", "must not be all 0", ""});
        }
        const std::string name =
            c.name.empty() ? default_channel_name(c, config.structure.excitation.direction)
                           : c.name;
        if (std::find(taken.begin(), taken.end(), name) != taken.end()) {
            out.push_back({key + ".name", text(name),
                           "is taken by another channel of the recording: give each a name of "
                           "its own",
                           ""});
        }
        taken.push_back(name);
    }
}

/// [campaign.random]: a band inside what the drive can make, on a force excitation that
/// takes any waveform, not together with a run from rest.
void check_random(const CampaignConfig& config, Violations& out) {
    const RandomSpec& random = config.campaign.random;
    if (!random.on()) return;
    const auto number = [](double v) { return config::number_text(v); };
    if (!(random.low_hz > 0.0) || !(random.low_hz < random.high_hz)) {
        out.push_back(
            {"campaign.random.low_hz", number(random.low_hz),
             "must be > 0 and below campaign.random.high_hz (" + number(random.high_hz) + ")", ""});
    } else if ((random.high_hz - random.low_hz) / random.resolution_hz < 8.0) {
        out.push_back({"campaign.random.resolution_hz", number(random.resolution_hz),
                       "must give at least 8 lines in the band " + number(random.low_hz) + "-" +
                           number(random.high_hz) + " Hz",
                       ""});
    }
    if (config.structure.excitation.kind != structure::ExcitationSpec::Kind::force) {
        out.push_back({"campaign.random.high_hz", number(random.high_hz),
                       "needs a force excitation (structure.excitation.kind = \"force\"): a "
                       "base's random displacement is not integrated",
                       ""});
    }
    if (config.physics.shaker.on()) {
        out.push_back({"campaign.random.high_hz", number(random.high_hz),
                       "cannot drive through [physics.shaker]: its coil is modelled in the "
                       "steady state of one frequency",
                       ""});
    }
    if (config.campaign.transient.on()) {
        out.push_back({"campaign.random.high_hz", number(random.high_hz),
                       "cannot go with campaign.transient.duration_s > 0: a sweep is one or the "
                       "other",
                       ""});
    }
}

/// Every point, mass and arrangement the campaign names must exist.
Violations check_references(const CampaignConfig& config) {
    Violations out;
    const auto names = point_names(config.structure);
    const auto known = [&](const std::string& name) {
        return std::find(names.begin(), names.end(), name) != names.end();
    };
    const auto text = [](const std::string& s) { return config::quoted(s); };
    if (!config.campaign.levels().empty() && !known(config.campaign.control_point)) {
        out.push_back({"campaign.control_point", text(config.campaign.control_point),
                       "must name a point of the structure", ""});
    }
    for (const auto& p : config.campaign.response_points) {
        if (!known(p)) {
            out.push_back(
                {"campaign.response_points", text(p), "must name a point of the structure", ""});
        }
    }
    check_channels(config, known, out);
    const TransientSpec& transient = config.campaign.transient;
    if (transient.on() && !config.campaign.drive.fixed()) {
        out.push_back({"campaign.transient.duration_s", config::number_text(transient.duration_s),
                       "needs campaign.drive.kind = \"fixed\": a run from rest drives each "
                       "amplitude unchanged",
                       ""});
    }
    if (transient.on() && !transient.frequency_hz) {
        out.push_back({"campaign.transient.frequency_hz", "absent",
                       "is required with campaign.transient.duration_s > 0", ""});
    }
    check_random(config, out);
    for (const auto& name : config.campaign.arrangement_selection) {
        const auto& defined = config.campaign.arrangements;
        if (std::none_of(defined.begin(), defined.end(),
                         [&](const ArrangementSpec& a) { return a.name == name; })) {
            out.push_back({"campaign.arrangements", text(name),
                           "must name a table [arrangements." + name + "]", ""});
        }
    }
    const auto beam = config.structure.beam.resolved();
    for (const auto& d : config.campaign.dampers) {
        const std::string key = config::join_path("dampers", d.name);
        if (!known(d.point)) {
            out.push_back(
                {key + ".point", text(d.point), "must name a point of the structure", ""});
        }
        if (d.enclosure_mass.empty()) continue;
        double point_x = -1.0;
        for (const auto& p : beam.points) {
            if (p.name == d.point) point_x = p.x_m;
        }
        using Kind = structure::StructureSpec::Kind;
        const auto& imported = config.structure.matrix.masses;
        const bool at_point =
            config.structure.kind == Kind::beam
                ? std::any_of(
                      beam.masses.begin(), beam.masses.end(),
                      [&](const auto& m) { return m.name == d.enclosure_mass && m.x_m == point_x; })
                : config.structure.kind == Kind::matrix &&
                      std::any_of(imported.begin(), imported.end(), [&](const auto& m) {
                          return (m.name.empty() ? m.point : m.name) == d.enclosure_mass &&
                                 m.point == d.point;
                      });
        if (!at_point) {
            out.push_back({key + ".enclosure_mass", text(d.enclosure_mass),
                           "must name a [[structure.beam.masses]] or [[structure.matrix.masses]] "
                           "entry at point \"" +
                               d.point + "\"",
                           ""});
        }
    }
    return out;
}

std::shared_ptr<const config::Table> build_campaign_schema() {
    TableBuilder<CampaignConfig> root("a campaign config");
    root.table(
        "campaign", [](CampaignConfig & c) -> auto& { return c; }, campaign_table());
    root.named_tables(
        "arrangements", [](CampaignConfig & c) -> auto& { return c.campaign.arrangements; },
        [](ArrangementSpec & a) -> auto& { return a.name; }, arrangement_table());
    root.named_tables(
        "dampers", [](CampaignConfig & c) -> auto& { return c.campaign.dampers; },
        [](DamperSpec & d) -> auto& { return d.name; }, schema::damper_table());
    root.table(
        "controller", [](CampaignConfig & c) -> auto& { return c.campaign.controller; },
        controller_table());
    root.table(
        "output", [](CampaignConfig & c) -> auto& { return c.campaign.output; }, output_table());
    root.table(
        "physics", [](CampaignConfig & c) -> auto& { return c.physics; }, physics_table());
    root.table(
            "structure", [](CampaignConfig & c) -> auto& { return c.structure; },
            schema::structure_table())
        .required();
    root.check([](const CampaignConfig& c) {
        Violations out = check_references(c);
        if (c.physics.air_drag.on() && c.structure.kind != structure::StructureSpec::Kind::beam) {
            out.push_back({"physics.air_drag.drag_coefficient",
                           config::number_text(c.physics.air_drag.drag_coefficient),
                           "needs a beam structure (structure.kind = \"beam\")",
                           "the drag acts on the beam's wide face"});
        }
        const auto names = point_names(c.structure);
        const auto check_point = [&](bool on, const std::string& point, const std::string& key) {
            if (on && std::find(names.begin(), names.end(), point) == names.end()) {
                out.push_back({key, config::quoted(point), "must name a point of the structure",
                               "where the physics acts"});
            }
        };
        check_point(c.physics.microslip.on(), c.physics.microslip.point, "physics.microslip.point");
        check_point(c.physics.cubic_spring.on(), c.physics.cubic_spring.point,
                    "physics.cubic_spring.point");
        check_point(c.physics.iwan_joint.on(), c.physics.iwan_joint.point,
                    "physics.iwan_joint.point");
        const ShakerSpec& shaker = c.physics.shaker;
        if (shaker.on() && c.structure.excitation.kind != structure::ExcitationSpec::Kind::force) {
            out.push_back({"physics.shaker.force_factor_n_per_a",
                           config::number_text(shaker.force_factor_n_per_a),
                           "needs a force-excited structure (structure.excitation.kind = "
                           "\"force\")",
                           "the shaker drives the structure's excitation point through a stinger"});
        }
        const DriveSpec& drive = c.campaign.drive;
        if (drive.fixed() && drive.amplitudes.empty()) {
            out.push_back({"campaign.drive.amplitudes", "[]",
                           "is required with campaign.drive.kind = \"fixed\"",
                           "peak amplitudes of a fixed drive, one sweep each"});
        }
        if (drive.fixed() && !c.campaign.levels_g.empty()) {
            out.push_back({"campaign.levels_g", config::number_text(c.campaign.levels_g.front()),
                           "is not used with campaign.drive.kind = \"fixed\" (its levels are "
                           "campaign.drive.amplitudes)",
                           "target RMS levels of the controller"});
        }
        if (!drive.fixed() && !drive.amplitudes.empty()) {
            out.push_back({"campaign.drive.amplitudes",
                           config::number_text(drive.amplitudes.front()),
                           "needs campaign.drive.kind = \"fixed\"",
                           "the controller sets the amplitudes of a controlled drive"});
        }
        if (drive.fixed() && drive.quantity == DriveSpec::Quantity::base_displacement &&
            c.structure.excitation.kind != structure::ExcitationSpec::Kind::base) {
            out.push_back({"campaign.drive.quantity", "\"base-displacement\"",
                           "needs base excitation (structure.excitation.kind = \"base\")",
                           "what a fixed amplitude is"});
        }
        return out;
    });
    return root.build();
}

}  // namespace

const config::Table& campaign_schema() {
    static const std::shared_ptr<const config::Table> schema = build_campaign_schema();
    return *schema;
}

}  // namespace sb::bench

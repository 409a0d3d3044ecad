// Reading the campaign tables of a config.
#include "bench/campaign_reader.hpp"

#include <algorithm>
#include <cmath>

#include "bench/damper_config.hpp"

namespace sb::bench {
namespace {

FrequencyGridSpec read_frequencies(Section s) {
    FrequencyGridSpec g;
    g.values_hz = s.numbers("values_hz", "explicit frequency grid [Hz]");
    g.low_ratio = s.number("low_ratio", g.low_ratio, "lowest frequency / first mode [-]");
    g.high_ratio = s.number("high_ratio", g.high_ratio, "highest frequency / first mode [-]");
    g.count = s.integer("count", g.count, "points of the built grid");
    g.grid_damping_ratio = s.number("grid_damping_ratio", g.grid_damping_ratio,
                                    "damping that places the built grid [-]");
    g.descending = s.choice("direction", "up", {"up", "down"}, "sweep direction") == "down";
    for (std::size_t i = 0; i < g.values_hz.size(); ++i) {
        if (!(g.values_hz[i] > 0.0)) {
            s.error("values_hz", format_value(g.values_hz[i]), "every value must be > 0",
                    "explicit frequency grid [Hz]");
        }
    }
    Violations v;
    require_positive(v, "low_ratio", g.low_ratio, "lowest frequency / first mode [-]");
    if (!(g.high_ratio > g.low_ratio)) {
        v.push_back({"high_ratio", format_value(g.high_ratio), "must be > low_ratio",
                     "highest frequency / first mode [-]"});
    }
    if (g.count < 2) {
        v.push_back({"count", std::to_string(g.count), "must be >= 2", "points of the grid"});
    }
    require_in_range(v, "grid_damping_ratio", g.grid_damping_ratio, 1e-4, 0.5,
                     "damping that places the built grid [-]");
    s.finish();
    s.report(v);
    return g;
}

std::vector<ArrangementSpec> read_arrangements(Section s) {
    std::vector<ArrangementSpec> out;
    for (auto& [name, a] : s.named_tables("an arrangement")) {
        ArrangementSpec spec;
        spec.name = name;
        spec.oscillation = a.choice("oscillation", "horizontal", {"horizontal", "vertical"},
                                    "direction of the beam's motion") == "vertical"
                               ? ArrangementSpec::Oscillation::vertical
                               : ArrangementSpec::Oscillation::horizontal;
        spec.damper_angle_deg =
            a.number("damper_angle_deg", 0.0, "angle between damper axis and motion [deg]");
        spec.block_mass_kg =
            a.number("block_mass_kg", 0.0, "mounting block mass at each damper [kg]");
        spec.block_cathetus_m =
            a.number("block_cathetus_m", 0.0, "cathetus of the 45-degree mounting wedge [m]");
        spec.mount_lift_m = a.vector3("mount_lift_m", spec.mount_lift_m,
                                      "further displacement of the mounting face [m]");
        Violations v;
        require_non_negative(v, "block_cathetus_m", spec.block_cathetus_m,
                             "cathetus of the 45-degree mounting wedge [m]");
        if (spec.block_cathetus_m > 0.0 && std::abs(spec.damper_angle_deg - 45.0) > 1e-9) {
            v.push_back({"block_cathetus_m", format_value(spec.block_cathetus_m),
                         "a right isosceles wedge tilts the damper by 45 deg: damper_angle_deg "
                         "must be 45, not " +
                             format_value(spec.damper_angle_deg),
                         "cathetus of the 45-degree mounting wedge [m]"});
        }
        require_in_range(v, "damper_angle_deg", spec.damper_angle_deg, 0.0, 90.0,
                         "angle between damper axis and motion [deg]");
        require_non_negative(v, "block_mass_kg", spec.block_mass_kg, "mounting block [kg]");
        a.finish();
        a.report(v);
        out.push_back(std::move(spec));
    }
    s.finish();
    return out;
}

control::ControllerOptions read_controller(Section s) {
    control::ControllerOptions c;
    c.tolerance = s.number("tolerance", c.tolerance, "relative RMS tolerance [-]");
    c.window_periods = s.integer("window_periods", c.window_periods, "settling window [periods]");
    c.early_periods = s.integer("early_periods", c.early_periods, "early decision [periods]");
    c.transient_periods =
        s.integer("transient_periods", c.transient_periods, "skipped after a change [periods]");
    c.max_periods = s.integer("max_periods", c.max_periods, "budget per point [periods]");
    c.closest_rerun_periods = s.integer("closest_rerun_periods", c.closest_rerun_periods,
                                        "re-run of the closest amplitude [periods]");
    c.initial_amplitude =
        s.number("initial_amplitude", 0.0, "first amplitude [N]; 0: from the linear model");
    c.min_amplitude = s.number("min_amplitude", c.min_amplitude, "lowest amplitude [N]");
    c.max_amplitude = s.number("max_amplitude", c.max_amplitude, "highest amplitude [N]");
    c.max_step_factor = s.number("max_step_factor", c.max_step_factor, "largest update factor");
    c.overshoot = s.number("overshoot", c.overshoot, "bracket widening [-]");
    c.limit_cycle_jump = s.number("limit_cycle_jump", c.limit_cycle_jump,
                                  "two-period limit cycle jump / tolerance [-]");
    c.limit_cycle_periods = s.integer("limit_cycle_periods", c.limit_cycle_periods,
                                      "alternating periods of a limit cycle");
    c.max_restarts = s.integer("max_restarts", c.max_restarts, "secant restarts");
    c.drift_horizon_periods = s.integer("drift_horizon_periods", c.drift_horizon_periods,
                                        "periods a drift in the window is extrapolated over");
    s.finish();
    control::ControllerOptions checked = c;
    if (checked.initial_amplitude == 0.0) {
        checked.initial_amplitude = 1.0;  // automatic: from the linear model
    }
    s.report(checked.validate());
    return c;
}

OutputSpec read_output(Section s) {
    OutputSpec o;
    o.series = s.boolean("series", o.series, "time histories of the steady windows");
    o.series_samples_per_period =
        s.integer("series_samples_per_period", o.series_samples_per_period, "samples per period");
    o.uff = s.boolean("uff", o.uff, "transfer functions as UFF58");
    o.plots = s.boolean("plots", o.plots, "SVG plots through gnuplot");
    if (o.series_samples_per_period < 8) {
        s.error("series_samples_per_period", std::to_string(o.series_samples_per_period),
                "must be >= 8", "samples per period");
    }
    s.finish();
    return o;
}

}  // namespace

CampaignSpec read_campaign(Section& root, Section& campaign) {
    CampaignSpec spec;
    spec.levels_g = campaign.numbers("levels_g", "target RMS levels at the control point [g]");
    for (double level : spec.levels_g) {
        if (!(level > 0.0)) {
            campaign.error("levels_g", format_value(level), "every level must be > 0",
                           "target RMS levels [g]");
        }
    }
    spec.control_point = campaign.string("control_point", "damper",
                                         "named point whose RMS acceleration is controlled");
    const int seed = campaign.integer("seed", 1, "seed of the particle filling");
    if (seed < 0) {
        campaign.error("seed", std::to_string(seed), "must be >= 0",
                       "seed of the particle filling");
    }
    spec.seed = static_cast<std::uint64_t>(std::max(0, seed));
    const std::string point_start =
        campaign.choice("point_start", "previous-state",
                        {"previous-state", "linear-steady-state", "equivalent-steady-state"},
                        "how the structure starts each point after the first");
    spec.point_start = point_start == "linear-steady-state"
                           ? CampaignSpec::PointStart::linear_steady_state
                       : point_start == "equivalent-steady-state"
                           ? CampaignSpec::PointStart::equivalent_steady_state
                           : CampaignSpec::PointStart::previous_state;
    spec.scale_response_on_update =
        campaign.boolean("scale_response_on_update", true,
                         "scale the structure's harmonic response with every amplitude update");
    spec.response_points =
        campaign.strings("response_points", "named points recorded besides the control point");
    const std::vector<std::string> wanted =
        campaign.strings("arrangements", "arrangements to run (default: all defined)");
    spec.frequencies = read_frequencies(campaign.table("frequencies", "the frequency grid"));
    auto defined = read_arrangements(root.table("arrangements", "mountings of the specimen"));
    if (wanted.empty()) {
        spec.arrangements = defined;
    }
    for (const auto& name : wanted) {
        const auto it = std::find_if(defined.begin(), defined.end(),
                                     [&](const auto& a) { return a.name == name; });
        if (it == defined.end()) {
            campaign.error("arrangements", "\"" + name + "\"",
                           "must name a table [arrangements." + name + "]", "arrangements to run");
        } else {
            spec.arrangements.push_back(*it);
        }
    }
    spec.dampers = read_dampers(root.table("dampers", "particle dampers"));
    spec.controller = read_controller(root.table("controller", "the RMS amplitude controller"));
    spec.output = read_output(root.table("output", "what the campaign writes"));
    return spec;
}

}  // namespace sb::bench

// The DEM time step a contact law needs: the largest step at which single impacts give the
// restitution of the converged integration.
#pragma once

#include <string>

#include "dem/options.hpp"
#include "dem/setup.hpp"

namespace sb::dem {

/// The steps tried, as fractions of the pair contact time, largest first.
inline constexpr double kTimeStepLadder[] = {1.0 / 10.0, 1.0 / 14.0, 1.0 / 20.0, 1.0 / 28.0,
                                             1.0 / 40.0, 1.0 / 56.0, 1.0 / 80.0};
/// The step whose restitution stands for the converged one (a fourth of the finest tried).
inline constexpr double kConvergedTimeStepFraction = 1.0 / 320.0;
/// Largest relative deviation of the restitution from the converged one, over the start
/// phases on average and at the worst phase. A bed's impacts start at every phase, so the
/// mean is the systematic error it feels; the spread over the phases acts as a random
/// scatter of each impact's restitution, bounded at 2 %: at the worst phase of t_c/10 paper
/// 000's e = 0.9 deviates by 1.6 %, and forty fillings of its damper alone at 0.5 and 0.75 g
/// and sixteen of its campaign at 0.5-3 g move by no more than chance between t_c/10 and
/// t_c/20 (docs/validation.md, the production time step).
inline constexpr double kRestitutionMeanTolerance = 0.005;
inline constexpr double kRestitutionWorstTolerance = 0.02;

/// What automatic_time_step_fraction() found.
struct TimeStepFraction {
    double fraction = 0.0;  ///< dt / pair contact time [-]
    /// Relative deviation of the restitution from the converged step's at `fraction`: mean over
    /// the start phases of the pair and the wall impact, and the worst single impact [-].
    double pair_mean_deviation = 0.0;
    double wall_mean_deviation = 0.0;
    double worst_deviation = 0.0;
    double pair_restitution = 0.0;  ///< converged, pair impact [-]
    double wall_restitution = 0.0;  ///< converged, wall impact [-]
    bool met = true;  ///< false: even the finest step of the ladder missed the tolerances
    std::string describe() const;
};

/// Restitution of one head-on normal impact of spheres of diameter `d` at closing speed `v`
/// with step `dt`, the contact starting `phase` (0..1) of a step's travel before the first
/// step's end: two spheres (`wall` false) or one onto the floor of a box, no gravity, with the
/// law, coefficients and stiffness of `options`.
double head_on_restitution(const SolverOptions& options, double d, bool wall, double v, double dt,
                           double phase);

/// The largest fraction of kTimeStepLadder at which the semi-implicit Euler step reproduces
/// the restitution of single normal impacts at `impact_speed_m_s` within the tolerances
/// above: two of the smallest spheres head on, and one onto a flat wall, with the law,
/// coefficients and stiffness of `options` (its enclosure, gravity and lock are not used).
/// Each impact is run from eight start phases of the step, (k + 1/2)/8 of a step's travel
/// from contact: where a contact starts and ends within a step is an O(dt) error whose sign
/// follows the phase, so one impact alone says little. The reference is the mean at
/// kConvergedTimeStepFraction, so that only the step's error is measured, not how well a
/// dashpot's constant matches the restitution asked for (tests/dem/contact_law_test.cpp).
/// The finest step of the ladder when none meets them (`met` false). Throws
/// std::invalid_argument for a non-positive contact time or speed.
TimeStepFraction automatic_time_step_fraction(const SolverOptions& options,
                                              double pair_contact_time_s, double impact_speed_m_s);

/// `chosen` (choose_contact()) with the time step automatic_time_step_fraction() finds for
/// the law of `options` at chosen.stiffness, and its log saying so.
ExcitationContact with_automatic_time_step(ExcitationContact chosen, SolverOptions options);

}  // namespace sb::dem

// The campaign specs: constraints across keys and the DEM options they give.
#include "bench/campaign_spec.hpp"

#include <algorithm>
#include <cmath>

#include "dem/time_step.hpp"

namespace sb::bench {

Violations ArrangementSpec::validate() const {
    Violations out;
    if (block_cathetus_m > 0.0 && std::abs(damper_angle_deg - 45.0) > 1e-9) {
        out.push_back({"block_cathetus_m", format_value(block_cathetus_m),
                       "a right isosceles wedge tilts the damper by 45 deg: damper_angle_deg "
                       "must be 45, not " +
                           format_value(damper_angle_deg),
                       "cathetus of the 45-degree mounting wedge [m]"});
    }
    return out;
}

Violations FrequencyGridSpec::validate() const {
    Violations out;
    if (values_hz.empty() && !(high_ratio > low_ratio)) {
        out.push_back({"high_ratio", format_value(high_ratio),
                       "must be > low_ratio = " + format_value(low_ratio),
                       "highest frequency / first mode [-]"});
    }
    return out;
}

double DriveSpec::excitation_amplitude(double amplitude, double frequency_hz) const {
    if (quantity == Quantity::excitation) return amplitude;
    const double omega = 2.0 * std::acos(-1.0) * frequency_hz;
    return omega * omega * amplitude;  // x = X sin(w t): its acceleration's amplitude w^2 X
}

dem::PairProperties ContactSpec::particle_wall() const {
    dem::PairProperties wall;
    wall.restitution = wall_restitution.value_or(particle_particle.restitution);
    wall.sliding_friction = wall_sliding_friction.value_or(particle_particle.sliding_friction);
    wall.rolling_friction = wall_rolling_friction.value_or(particle_particle.rolling_friction);
    wall.dissipative_constant_s =
        wall_dissipative_constant_s.value_or(particle_particle.dissipative_constant_s);
    wall.dashpot_n_s_per_m = wall_dashpot_n_s_per_m.value_or(particle_particle.dashpot_n_s_per_m);
    return wall;
}

namespace {

/// The wall's coefficients with those given in their place (the rods', the lateral
/// surface's); absent when none is given, so that the DEM uses the wall's own.
std::optional<dem::PairProperties> wall_pair_but(const dem::PairProperties& wall,
                                                 std::optional<double> restitution,
                                                 std::optional<double> sliding_friction,
                                                 std::optional<double> rolling_friction) {
    if (!restitution && !sliding_friction && !rolling_friction) return std::nullopt;
    dem::PairProperties own = wall;
    own.restitution = restitution.value_or(own.restitution);
    own.sliding_friction = sliding_friction.value_or(own.sliding_friction);
    own.rolling_friction = rolling_friction.value_or(own.rolling_friction);
    return own;
}

/// The wall's material with the moduli given in its place; absent when none is given.
std::optional<dem::Material> wall_material_but(const dem::Material& wall,
                                               std::optional<double> youngs_modulus_pa,
                                               std::optional<double> poisson_ratio) {
    if (!youngs_modulus_pa && !poisson_ratio) return std::nullopt;
    dem::Material own = wall;
    own.youngs_modulus_pa = youngs_modulus_pa.value_or(own.youngs_modulus_pa);
    own.poisson_ratio = poisson_ratio.value_or(own.poisson_ratio);
    return own;
}

}  // namespace

std::optional<dem::PairProperties> ContactSpec::particle_rod() const {
    return wall_pair_but(particle_wall(), rod_restitution, rod_sliding_friction,
                         rod_rolling_friction);
}

std::optional<dem::Material> ContactSpec::rod_material() const {
    return wall_material_but(wall_material, rod_youngs_modulus_pa, rod_poisson_ratio);
}

std::optional<dem::PairProperties> ContactSpec::particle_side() const {
    return wall_pair_but(particle_wall(), side_restitution, side_sliding_friction,
                         side_rolling_friction);
}

std::optional<dem::Material> ContactSpec::side_material() const {
    return wall_material_but(wall_material, side_youngs_modulus_pa, side_poisson_ratio);
}

dem::ContactOptions ContactSpec::contact_options(double stiffness) const {
    dem::ContactOptions c;
    c.normal = normal;
    c.damping = damping;
    c.tangential = tangential;
    c.rolling = rolling;
    c.normal_stiffness = stiffness;
    c.tangential_stiffness_ratio = tangential_stiffness_ratio;
    c.slip_regularisation_m_s = slip_regularisation_m_s;
    c.particle_particle = particle_particle;
    c.particle_wall = particle_wall();
    c.wall_material = wall_material;
    c.particle_rod = particle_rod();
    c.rod_material = rod_material();
    c.particle_side = particle_side();
    c.side_material = side_material();
    return c;
}

dem::SolverOptions DamperSpec::solver_options(double normal_stiffness) const {
    dem::SolverOptions s;
    s.particles = particles;
    s.contact = contact.contact_options(normal_stiffness);
    s.enclosure = enclosure;
    s.max_overlap_fraction = guard_overlap_fraction;
    s.threads = threads;
    s.lock = lock;
    if (locked) {
        s.lock = dem::LockOptions{};
        s.lock.fraction = 1.0;  // never released: release_time_s stays 0
    }
    return s;
}

dem::ExcitationContact DamperSpec::excitation_contact(double peak_acceleration_m_s2,
                                                      double frequency_hz) const {
    // An automatic step is sized from the pair contact time, whatever fraction stands in here.
    const double fraction = contact.time_step_fraction.value_or(dem::kTimeStepLadder[0]);
    const dem::ExcitationContact chosen =
        contact.stiffness_for == ContactSpec::StiffnessFor::materials
            ? dem::materials_contact(particles, enclosure, contact.contact_options(0.0), fraction,
                                     peak_acceleration_m_s2, frequency_hz)
            : dem::choose_contact(particles, enclosure, contact.normal,
                                  contact.particle_particle.restitution, contact.normal_stiffness,
                                  contact.max_overlap_fraction, fraction, peak_acceleration_m_s2,
                                  frequency_hz);
    if (contact.time_step_fraction) return chosen;
    return dem::with_automatic_time_step(chosen, solver_options(chosen.stiffness));
}

Violations DamperSpec::validate() const {
    // An automatic stiffness is chosen per sweep; any positive value stands in for it here.
    const dem::SolverOptions solver = solver_options(contact.normal_stiffness.value_or(1.0));
    Violations out;
    append_prefixed(out, "solver", solver.validate());
    append_prefixed(out, "settle", settle.validate());
    return out;
}

std::vector<ArrangementSpec> CampaignSpec::selected_arrangements() const {
    if (arrangement_selection.empty()) return arrangements;
    std::vector<ArrangementSpec> out;
    for (const auto& name : arrangement_selection) {
        const auto it = std::find_if(arrangements.begin(), arrangements.end(),
                                     [&](const ArrangementSpec& a) { return a.name == name; });
        if (it != arrangements.end()) out.push_back(*it);
    }
    return out;
}

}  // namespace sb::bench

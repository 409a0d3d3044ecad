// Attachments: the DEM damper, the rigid particles, the describing function, an air-drag strip.
#include "bench/attachment.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/units.hpp"
#include "dem/setup.hpp"

namespace sb::bench {

DemDamper::DemDamper(const dem::SolverOptions& options, const Eigen::Matrix3d& mount_rotation,
                     const Eigen::Vector3d& offset_m, const dem::ParticleSet& bed,
                     const Eigen::Vector3d& rest_position_m)
    : options_(options), mount_rotation_(mount_rotation), offset_m_(offset_m) {
    PointMotion rest;
    rest.position_m = rest_position_m;
    solver_ = std::make_unique<dem::Solver>(options_, bed, enclosure(rest));
}

dem::EnclosureState DemDamper::enclosure(const PointMotion& motion) const {
    const Eigen::Vector3d r = motion.rotation * offset_m_;
    dem::EnclosureState e;
    e.position_m = motion.position_m + r;
    e.rotation = motion.rotation * mount_rotation_;
    e.velocity_m_s = motion.velocity_m_s + motion.angular_velocity_rad_s.cross(r);
    e.angular_velocity_rad_s = motion.angular_velocity_rad_s;
    return e;
}

PointLoad DemDamper::step(const PointMotion& motion, double dt_s) {
    solver_->set_enclosure_state(enclosure(motion));
    solver_->step(dt_s);
    // The wall moment is about the enclosure origin; moved to the point: M + r x F.
    const Eigen::Vector3d r = motion.rotation * offset_m_;
    const Eigen::Vector3d force = solver_->wall_force();
    return {force, solver_->wall_moment() + r.cross(force)};
}

PointLoad DemDamper::weight() const {
    // The bed's centre of gravity from its enclosure-frame positions and the mounting (not
    // from the solver's world positions, which sit wherever its last pose was).
    const dem::ParticleSet local = solver_->local_snapshot();
    const auto& particles = solver_->particles();
    double mass_kg = 0.0;
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < particles.size(); ++k) {
        const double m = 1.0 / particles.inv_mass[k];
        mass_kg += m;
        first_moment += m * local.positions_m[k];
    }
    const Eigen::Vector3d w = mass_kg * options_.gravity_m_s2;
    const Eigen::Vector3d arm = offset_m_ + mount_rotation_ * (first_moment / mass_kg);
    return {w, arm.cross(w)};
}

HeldBody DemDamper::held_body() const {
    const dem::Solver::LockedBody locked = solver_->locked_body();
    HeldBody body;
    body.mass_kg = locked.mass_kg;
    body.centre_m = offset_m_ + mount_rotation_ * locked.centre_m;
    body.inertia_kg_m2 = mount_rotation_ * locked.inertia_kg_m2 * mount_rotation_.transpose();
    return body;
}

void DemDamper::carry_held_inertia_in_structure() {
    held_inertia_in_structure_ = true;
    solver_->set_locked_inertia_external(true);
}

AttachmentState DemDamper::state() const {
    return {solver_->state(), std::nullopt, std::nullopt, std::nullopt};
}

AttachmentState DemDamper::state_at(const PointMotion& motion) {
    // The pose the next step would set anyway: the state is then relative to it.
    solver_->set_enclosure_state(enclosure(motion));
    return {solver_->state(), std::nullopt, std::nullopt, std::nullopt};
}

namespace {
const dem::SolverState& dem_state(const AttachmentState& state) {
    if (!state.dem) {
        throw std::invalid_argument("a DEM damper's state must hold its particles, it holds none");
    }
    return *state.dem;
}
}  // namespace

void DemDamper::restore(const AttachmentState& state) {
    // At the state's own pose the solver continues bitwise as if never interrupted.
    const dem::SolverState& s = dem_state(state);
    continue_from(s, s.enclosure);
}

void DemDamper::restore_at(const AttachmentState& state, const PointMotion& motion) {
    continue_from(dem_state(state), enclosure(motion));
}

void DemDamper::continue_from(const dem::SolverState& state, const dem::EnclosureState& at) {
    solver_ = std::make_unique<dem::Solver>(options_, state, at);
    solver_->set_locked_inertia_external(held_inertia_in_structure_);
}

DescribingFunctionDamper::DescribingFunctionDamper(
    std::shared_ptr<const DescribingFunction> function, const Eigen::Vector3d& direction,
    const Eigen::Vector3d& rest_position_m, const PointLoad& weight)
    : function_(std::move(function)),
      direction_(direction.normalized()),
      rest_position_m_(rest_position_m),
      weight_(weight) {}

void DescribingFunctionDamper::set_frequency(double frequency_hz) {
    frequency_hz_ = frequency_hz;
    estimate_from_motion_ = true;
}

void DescribingFunctionDamper::update_value() {
    value_ = function_->evaluate(state_.acceleration_m_s2, frequency_hz_);
}

PointLoad DescribingFunctionDamper::step(const PointMotion& motion, double dt_s) {
    const double w = hz_to_rad_s(frequency_hz_);
    const double u = (motion.position_m - rest_position_m_).dot(direction_);
    const double v = motion.velocity_m_s.dot(direction_);
    if (estimate_from_motion_) {
        // A harmonic motion about u0: |a1| = w^2 sqrt((u - u0)^2 + (v / w)^2) at any instant.
        const double x = u - state_.mean_displacement_m;
        state_.acceleration_m_s2 = w * w * std::sqrt(x * x + v * v / (w * w));
        estimate_from_motion_ = false;
        steps_ = 0;
        sum_u_ = 0.0;
        sum_phasor_ = 0.0;
        update_value();
    }
    // The fundamental of u over each whole period since the point (or the frequency) began:
    // U1 = (2/N) sum u_k e^{-i w t_k}, |a1| = w^2 |U1|, u0 = sum u_k / N.
    sum_u_ += u;
    sum_phasor_ += u * std::polar(1.0, -w * dt_s * steps_);
    ++steps_;
    const int per_period = std::max(1, static_cast<int>(std::lround(1.0 / (frequency_hz_ * dt_s))));
    if (steps_ >= per_period) {
        state_.acceleration_m_s2 = w * w * 2.0 / steps_ * std::abs(sum_phasor_);
        state_.mean_displacement_m = sum_u_ / steps_;
        steps_ = 0;
        sum_u_ = 0.0;
        sum_phasor_ = 0.0;
        update_value();
    }
    // The coupled specimen applies this load at the END of the step (the structure
    // interpolates between the two ends): the motion is advanced by dt along the harmonic
    // motion it describes, x(t + dt) = x cos(w dt) + v/w sin(w dt), so that the load does not
    // lag by a step. A lag of w dt (2.5e-2 rad at 256 steps per period) turns the apparent
    // mass's stiffness M' w^2 into a dashpot M' w^2 dt, a third of the paper-000 beam's own
    // damping.
    const double x = u - state_.mean_displacement_m;
    const double c = std::cos(w * dt_s);
    const double s = std::sin(w * dt_s);
    const double x_end = x * c + v / w * s;
    const double v_end = v * c - w * x * s;
    const std::complex<double> m = value_.apparent_mass_kg;
    const double q = m.real() * w * w * x_end + w * m.imag() * v_end;
    return {weight_.force_n + q * direction_, weight_.moment_nm};
}

AttachmentState DescribingFunctionDamper::state() const {
    AttachmentState s;
    s.describing = state_;
    return s;
}

void DescribingFunctionDamper::restore(const AttachmentState& state) {
    if (state.describing) state_ = *state.describing;
    estimate_from_motion_ = true;
}

AirDragStrip::AirDragStrip(const Eigen::Vector3d& normal, double coefficient_kg_m)
    : normal_(normal.normalized()), coefficient_kg_m_(coefficient_kg_m) {}

PointLoad AirDragStrip::step(const PointMotion& motion, double) const {
    const double v = normal_.dot(motion.velocity_m_s);
    return {-coefficient_kg_m_ * std::abs(v) * v * normal_, Eigen::Vector3d::Zero()};
}

DescribingFunction::Value AirDragStrip::describing(double acceleration_m_s2,
                                                   double frequency_hz) const {
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    DescribingFunction::Value value;
    value.apparent_mass_kg = std::complex<double>(
        0.0, -8.0 / (3.0 * std::numbers::pi) * coefficient_kg_m_ * acceleration_m_s2 / (w * w));
    value.h2_ratio = 0.0;
    value.h3_ratio = 0.2;
    return value;
}

MicroslipDashpot::MicroslipDashpot(const Eigen::Vector3d& direction, double damping_n_s_per_m,
                                   double exponent, double reference_velocity_m_s)
    : direction_(direction.normalized()),
      damping_n_s_per_m_(damping_n_s_per_m),
      exponent_(exponent),
      reference_velocity_m_s_(reference_velocity_m_s) {}

PointLoad MicroslipDashpot::step(const PointMotion& motion, double) const {
    const double v = direction_.dot(motion.velocity_m_s);
    const double c =
        damping_n_s_per_m_ * std::pow(std::abs(v) / reference_velocity_m_s_, exponent_);
    return {-c * v * direction_, Eigen::Vector3d::Zero()};
}

DescribingFunction::Value MicroslipDashpot::describing(double acceleration_m_s2,
                                                       double frequency_hz) const {
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    const double v = acceleration_m_s2 / w;
    const double chi = exponent_;
    // The Fourier sine coefficients of |sin t|^chi sin t: b_k = (4 / pi) int_0^(pi/2)
    // sin^(1 + chi) t sin(k t) dt. With I_n = int_0^(pi/2) sin^n = (sqrt(pi) / 2)
    // Gamma((n + 1) / 2) / Gamma(n / 2 + 1) and I_(n+2) = (n + 1) / (n + 2) I_n:
    // b_1 = (4 / pi) I_(2 + chi) = kappa, and sin 3t = 3 sin t - 4 sin^3 t gives
    // b_3 / b_1 = 3 - 4 (3 + chi) / (4 + chi) = -chi / (4 + chi).
    const double kappa = 2.0 / std::sqrt(std::numbers::pi) * std::tgamma((3.0 + chi) / 2.0) /
                         std::tgamma((4.0 + chi) / 2.0);
    const double c_eq = damping_n_s_per_m_ * kappa * std::pow(v / reference_velocity_m_s_, chi);
    DescribingFunction::Value value;
    value.apparent_mass_kg = std::complex<double>(0.0, -c_eq / w);
    value.h2_ratio = 0.0;
    value.h3_ratio = chi / (4.0 + chi);
    return value;
}

CubicSpring::CubicSpring(const Eigen::Vector3d& direction, double stiffness_n_per_m3,
                         const Eigen::Vector3d& rest_position_m)
    : direction_(direction.normalized()),
      stiffness_n_per_m3_(stiffness_n_per_m3),
      rest_position_m_(rest_position_m) {}

PointLoad CubicSpring::step(const PointMotion& motion, double dt_s) const {
    // The coupled specimen applies the load at the step's end, so the spring reads the
    // displacement predicted there (as the Iwan joint's sliders do): from the step's start its
    // tangent stiffness 3 k3 u^2 would lag a step, a negative damping 3 k3 u^2 dt.
    const double u =
        direction_.dot(motion.position_m - rest_position_m_ + motion.velocity_m_s * dt_s);
    return {-stiffness_n_per_m3_ * u * u * u * direction_, Eigen::Vector3d::Zero()};
}

DescribingFunction::Value CubicSpring::describing(double acceleration_m_s2,
                                                  double frequency_hz) const {
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    const double u = acceleration_m_s2 / (w * w);
    DescribingFunction::Value value;
    value.apparent_mass_kg = -0.75 * stiffness_n_per_m3_ * u * u / (w * w);
    value.h2_ratio = 0.0;
    value.h3_ratio = 1.0 / 3.0;
    return value;
}

PointLoad step(Attachment& attachment, const PointMotion& motion, double dt_s) {
    return std::visit([&](auto& m) { return m.step(motion, dt_s); }, attachment.model);
}

PointLoad weight(const Attachment& attachment) {
    return std::visit([](const auto& m) { return m.weight(); }, attachment.model);
}

AttachmentState state(const Attachment& attachment) {
    return std::visit([](const auto& m) { return m.state(); }, attachment.model);
}

AttachmentState state_at(Attachment& attachment, const PointMotion& motion) {
    return std::visit([&](auto& m) { return m.state_at(motion); }, attachment.model);
}

void restore(Attachment& attachment, const AttachmentState& s) {
    std::visit([&](auto& m) { m.restore(s); }, attachment.model);
}

void restore_at(Attachment& attachment, const AttachmentState& s, const PointMotion& motion) {
    std::visit([&](auto& m) { m.restore_at(s, motion); }, attachment.model);
}

void set_frequency(Attachment& attachment, double frequency_hz) {
    std::visit([&](auto& m) { m.set_frequency(frequency_hz); }, attachment.model);
}

const dem::Solver* dem_solver(const Attachment& attachment) {
    if (const auto* d = std::get_if<DemDamper>(&attachment.model)) return &d->solver();
    return nullptr;
}

std::optional<std::string> bed_vtk_text(const Attachment& attachment) {
    const dem::Solver* solver = dem_solver(attachment);
    if (solver == nullptr) return std::nullopt;
    return dem::vtk_text(dem::local_particles(solver->state()));
}

}  // namespace sb::bench

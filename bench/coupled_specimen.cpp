// The structure with its particle dampers, stepped together.
#include "bench/coupled_specimen.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::bench {
namespace {

/// Rotation matrix of a small-rotation vector (exact exponential map, so the enclosure stays
/// rigid however large the beam's rotation).
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& theta) {
    const double angle = theta.norm();
    if (angle < 1e-300) {
        return Eigen::Matrix3d::Identity();
    }
    return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

}  // namespace

CoupledSpecimen::CoupledSpecimen(const structure::LinearModel& model,
                                 const structure::ModalBasis& basis,
                                 const structure::ExcitationSpec& excitation,
                                 std::vector<MountedDamper> dampers,
                                 std::vector<std::string> channel_points, double dt_max_s,
                                 int step_multiple)
    : model_(&model),
      basis_(&basis),
      start_model_(&model),
      start_basis_(&basis),
      excitation_(excitation),
      dampers_(std::move(dampers)),
      channel_points_(std::move(channel_points)),
      direction_(excitation.direction.normalized()),
      dt_max_s_(dt_max_s),
      step_multiple_(std::max(1, step_multiple)) {
    damper_loads_.assign(dampers_.size(), Eigen::Matrix<double, 6, 1>::Zero());
    if (!(dt_max_s_ > 0.0)) {
        throw std::invalid_argument("coupled specimen: the largest time step must be > 0");
    }
    names_.push_back(excitation_.kind == structure::ExcitationSpec::Kind::force ? "force"
                                                                                : "base_acc");
    for (const auto& p : channel_points_) {
        names_.push_back("acc_" + p);
    }
}

void CoupledSpecimen::set_start_model(const structure::LinearModel& model,
                                      const structure::ModalBasis& basis) {
    if (model.dofs() != model_->dofs()) {
        throw std::invalid_argument("coupled specimen: the start model has " +
                                    std::to_string(model.dofs()) + " free DOFs, the specimen " +
                                    std::to_string(model_->dofs()));
    }
    start_model_ = &model;
    start_basis_ = &basis;
}

double CoupledSpecimen::time_s() const { return structure_ ? structure_->time_s() : 0.0; }

void CoupledSpecimen::set_frequency(double frequency_hz) {
    if (!(frequency_hz > 0.0)) {
        throw std::invalid_argument("coupled specimen: frequency must be > 0");
    }
    const double period_s = 1.0 / frequency_hz;
    const int blocks = static_cast<int>(std::ceil(period_s / dt_max_s_ / step_multiple_ - 1e-9));
    steps_per_period_ = std::max(1, blocks) * step_multiple_;
    dt_s_ = period_s / steps_per_period_;
    frequency_hz_ = frequency_hz;

    SpecimenState kept;
    const bool had_state = structure_ != nullptr;
    if (had_state) {
        kept.q = structure_->q();
        kept.q_dot = structure_->q_dot();
    }
    structure_ = std::make_unique<structure::ReducedModalModel>(*model_, *basis_, dt_s_);
    damper_point_index_.clear();
    for (const auto& d : dampers_) {
        damper_point_index_.push_back(structure_->point_index(d.point));
    }
    channel_index_.clear();
    for (const auto& p : channel_points_) {
        channel_index_.push_back(structure_->point_index(p));
    }
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        shaker_index_ = structure_->point_index(excitation_.point);
    }
    if (had_state) {
        // A point starts at phase 0 of its own sine (whole periods before it end there too),
        // so the excitation is continuous across the frequency change.
        set_point_loads();
        set_excitation(0.0, 0.0);
        structure_->set_state(kept.q, kept.q_dot, 0.0);
    }
}

double CoupledSpecimen::excitation_value(double amplitude, double time_s) const {
    return amplitude * std::sin(hz_to_rad_s(frequency_hz_) * time_s);
}

void CoupledSpecimen::set_excitation(double amplitude, double time_s) {
    const double value = excitation_value(amplitude, time_s);
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        structure_->set_point_load(shaker_index_, value * direction_, Eigen::Vector3d::Zero());
    } else {
        const double w = hz_to_rad_s(frequency_hz_);
        const double phase = w * time_s;
        // a = A sin(wt): v = -A/w cos(wt), d = -A/w^2 sin(wt) (zero-mean harmonic motion).
        structure_->set_base_motion(-amplitude / (w * w) * std::sin(phase),
                                    -amplitude / w * std::cos(phase), value);
    }
}

void CoupledSpecimen::apply_damper_loads() {
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        const auto& d = dampers_[i];
        if (!d.solver) {
            continue;
        }
        const Eigen::Vector3d r =
            rotation_of(structure_->rotation(damper_point_index_[i])) * d.offset_m;
        const Eigen::Vector3d force = d.solver->wall_force();
        // The wall moment is about the enclosure origin; moved to the point: M + r x F.
        damper_loads_[i] << force, d.solver->wall_moment() + r.cross(force);
    }
    set_point_loads();
}

void CoupledSpecimen::set_point_loads() {
    // Several dampers may share a point: their loads add up.
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        bool first_at_point = true;
        Eigen::Matrix<double, 6, 1> total = Eigen::Matrix<double, 6, 1>::Zero();
        for (std::size_t j = 0; j < dampers_.size(); ++j) {
            if (damper_point_index_[j] == damper_point_index_[i]) {
                first_at_point = first_at_point && j >= i;
                total += damper_loads_[j];
            }
        }
        if (first_at_point) {
            structure_->set_point_load(damper_point_index_[i], total.head<3>(), total.tail<3>());
        }
    }
}

void CoupledSpecimen::start_from_linear_steady_state(double amplitude, double time_s,
                                                     std::complex<double> response_ratio) {
    if (!structure_) {
        throw std::logic_error("coupled specimen: set_frequency before starting");
    }
    // The enclosures jump with the structure: the particles go with them, keeping their
    // positions and velocities relative to their enclosure.
    std::vector<dem::ParticleSet> local;
    for (const auto& d : dampers_) {
        local.push_back(d.solver ? d.solver->local_snapshot() : dem::ParticleSet{});
    }
    // The start model's steady state in physical DOFs, x = Phi_s q_s, projected on the
    // specimen's mass-normalised modes: q = Phi^T M x (both models share their free DOFs).
    structure::ReducedModalModel start(*start_model_, *start_basis_, dt_s_);
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        start.set_harmonic_steady_state(excitation_.point, direction_, amplitude, frequency_hz_,
                                        time_s);
        structure_->set_harmonic_steady_state(excitation_.point, direction_, amplitude,
                                              frequency_hz_, time_s);
    } else {
        start.set_harmonic_base_steady_state(amplitude, frequency_hz_, time_s);
        structure_->set_harmonic_base_steady_state(amplitude, frequency_hz_, time_s);
    }
    const int start_modes = start.modes();
    const Eigen::MatrixXd projection = basis_->shapes.leftCols(structure_->modes()).transpose() *
                                       model_->mass() * start_basis_->shapes.leftCols(start_modes);
    Eigen::VectorXd q_linear = projection * start.q();
    Eigen::VectorXd q_dot_linear = projection * start.q_dot();
    if (response_ratio != 1.0) {
        // q(t) = Re{Q e^{iw(t - t0)}}: Q = q - i q_dot / w at t0; the state of c Q.
        const double w = hz_to_rad_s(frequency_hz_);
        const Eigen::VectorXcd phasor =
            (q_linear.cast<std::complex<double>>() -
             std::complex<double>(0.0, 1.0 / w) * q_dot_linear.cast<std::complex<double>>()) *
            response_ratio;
        q_linear = phasor.real();
        q_dot_linear = -w * phasor.imag();
    }
    // Static deflection under the particles' weight at rest on the walls, so that the weight
    // does not start a transient: q_s = phi^T f_w / omega^2.
    Eigen::VectorXd q = q_linear;
    const int modes = structure_->modes();
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        const auto& d = dampers_[i];
        if (!d.solver) {
            continue;
        }
        // The bed's centre of gravity from its enclosure-frame positions and the mounting
        // (not from the solver's world positions, which sit wherever its last pose was).
        double mass_kg = 0.0;
        Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
        const auto& state = d.solver->particles();
        for (std::size_t k = 0; k < state.size(); ++k) {
            const double m = 1.0 / state.inv_mass[k];
            mass_kg += m;
            first_moment += m * local[i].positions_m[k];
        }
        const Eigen::Vector3d weight = mass_kg * d.solver->options().gravity_m_s2;
        const Eigen::Vector3d arm = d.offset_m + d.mount_rotation * (first_moment / mass_kg);
        const Eigen::VectorXd f = model_->point_load(d.point, weight, arm.cross(weight));
        for (int m = 0; m < modes; ++m) {
            const double w = basis_->modes[static_cast<std::size_t>(m)].frequency_hz * kTwoPi;
            q[m] += basis_->shapes.col(m).dot(f) / (w * w);
        }
        damper_loads_[i] << weight, arm.cross(weight);
    }
    set_point_loads();
    structure_->set_state(q, q_dot_linear, time_s);
    rebuild_solvers(local);
}

void CoupledSpecimen::step(double amplitude, std::vector<double>& values) {
    const double dt = dt_s_;
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        auto& d = dampers_[i];
        if (!d.solver) {
            continue;
        }
        d.solver->set_enclosure_state(enclosure_state(i));
        d.solver->step(dt);
    }
    apply_damper_loads();
    const double t_next = structure_->time_s() + dt;
    set_excitation(amplitude, t_next);
    structure_->step();

    values.resize(names_.size());
    values[0] = excitation_value(amplitude, structure_->time_s());
    for (std::size_t c = 0; c < channel_index_.size(); ++c) {
        values[c + 1] = structure_->acceleration(channel_index_[c]).dot(direction_);
    }
}

dem::EnclosureState CoupledSpecimen::enclosure_state(std::size_t damper) const {
    const auto& d = dampers_[damper];
    const int p = damper_point_index_[damper];
    const Eigen::Matrix3d small = rotation_of(structure_->rotation(p));
    const Eigen::Vector3d r = small * d.offset_m;
    const Eigen::Vector3d omega = structure_->angular_velocity(p);
    dem::EnclosureState enclosure;
    enclosure.position_m = model_->point(d.point).position_m + structure_->displacement(p) + r;
    enclosure.rotation = small * d.mount_rotation;
    enclosure.velocity_m_s = structure_->velocity(p) + omega.cross(r);
    enclosure.angular_velocity_rad_s = omega;
    return enclosure;
}

const Eigen::VectorXd& CoupledSpecimen::modal_displacement() const {
    if (!structure_) {
        throw std::logic_error("coupled specimen: no structure state before set_frequency()");
    }
    return structure_->q();
}

void CoupledSpecimen::scale_response(double ratio, const Eigen::VectorXd& q_mean) {
    const Eigen::VectorXd& q = modal_displacement();
    const Eigen::VectorXd scaled = q_mean + ratio * (q - q_mean);
    const Eigen::VectorXd scaled_rate = ratio * structure_->q_dot();
    // The beds ride with their enclosures through the jump: same enclosure-frame positions
    // and relative velocities, as between two points (restore()), so the jump itself starts
    // no impacts.
    std::vector<dem::ParticleSet> local(dampers_.size());
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        if (dampers_[i].solver) {
            local[i] = dampers_[i].solver->local_snapshot();
        }
    }
    structure_->set_state(scaled, scaled_rate, structure_->time_s());
    rebuild_solvers(local);
}

SpecimenState CoupledSpecimen::state() const {
    SpecimenState s;
    s.q = structure_->q();
    s.q_dot = structure_->q_dot();
    s.damper_loads = damper_loads_;
    for (const auto& d : dampers_) {
        s.particles.push_back(d.solver ? d.solver->local_snapshot() : dem::ParticleSet{});
    }
    return s;
}

void CoupledSpecimen::restore(const SpecimenState& state) {
    if (!structure_) {
        throw std::logic_error("coupled specimen: set_frequency before restoring");
    }
    if (state.particles.size() != dampers_.size() || state.damper_loads.size() != dampers_.size()) {
        throw std::invalid_argument("coupled specimen: state has " +
                                    std::to_string(state.particles.size()) +
                                    " dampers, the specimen " + std::to_string(dampers_.size()));
    }
    damper_loads_ = state.damper_loads;
    set_point_loads();
    set_excitation(0.0, 0.0);
    structure_->set_state(state.q, state.q_dot, 0.0);
    rebuild_solvers(state.particles);
}

void CoupledSpecimen::rebuild_solvers(const std::vector<dem::ParticleSet>& local) {
    for (std::size_t i = 0; i < dampers_.size(); ++i) {
        auto& d = dampers_[i];
        if (!d.solver) {
            continue;
        }
        const dem::SolverOptions options = d.solver->options();
        d.solver = std::make_unique<dem::Solver>(options, local[i], enclosure_state(i));
    }
}

}  // namespace sb::bench

// The structure with its attachments, stepped together.
#include "bench/coupled_specimen.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"
#include "structure/rigid_mass.hpp"

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
                                 std::vector<Attachment> attachments,
                                 std::vector<RecordedChannel> channels, double dt_max_s,
                                 int step_multiple)
    : model_(&model),
      basis_(&basis),
      start_model_(&model),
      start_basis_(&basis),
      excitation_(excitation),
      attachments_(std::move(attachments)),
      channels_(std::move(channels)),
      direction_(excitation.direction.normalized()),
      dt_max_s_(dt_max_s),
      step_multiple_(std::max(1, step_multiple)) {
    loads_.assign(attachments_.size(), Eigen::Matrix<double, 6, 1>::Zero());
    next_loads_ = loads_;
    held_counts_.assign(attachments_.size(), 0);
    held_bodies_.assign(attachments_.size(), HeldBody{});
    if (!(dt_max_s_ > 0.0)) {
        throw std::invalid_argument("coupled specimen: the largest time step must be > 0");
    }
    names_.push_back(excitation_.kind == structure::ExcitationSpec::Kind::force ? "force"
                                                                                : "base_acc");
    // A damper-force channel reads its attachment's load: found once, by name.
    channel_index_.assign(channels_.size(), -1);
    for (std::size_t c = 0; c < channels_.size(); ++c) {
        names_.push_back(channels_[c].name);
        if (channels_[c].quantity != RecordedChannel::Quantity::damper_force) continue;
        const auto found =
            std::find_if(attachments_.begin(), attachments_.end(),
                         [&](const Attachment& a) { return a.name == channels_[c].damper; });
        if (found == attachments_.end()) {
            throw std::invalid_argument("coupled specimen: channel " + channels_[c].name +
                                        " reads the force of \"" + channels_[c].damper +
                                        "\", which is attached nowhere");
        }
        channel_index_[c] = static_cast<int>(found - attachments_.begin());
    }
}

namespace {

std::vector<RecordedChannel> accelerations_along(const std::vector<std::string>& points,
                                                 const Eigen::Vector3d& direction) {
    std::vector<RecordedChannel> out;
    for (const auto& p : points) out.push_back(acceleration_channel(p, direction));
    return out;
}

}  // namespace

CoupledSpecimen::CoupledSpecimen(const structure::LinearModel& model,
                                 const structure::ModalBasis& basis,
                                 const structure::ExcitationSpec& excitation,
                                 std::vector<Attachment> attachments,
                                 const std::vector<std::string>& channel_points, double dt_max_s,
                                 int step_multiple)
    : CoupledSpecimen(model, basis, excitation, std::move(attachments),
                      accelerations_along(channel_points, excitation.direction), dt_max_s,
                      step_multiple) {}

void CoupledSpecimen::drive_through(const ShakerSpec& shaker) {
    if (excitation_.kind != structure::ExcitationSpec::Kind::force) {
        throw std::invalid_argument("coupled specimen: a shaker drives a force excitation");
    }
    shaker_ = shaker;
    names_.front() = "voltage";
    names_.push_back("force");
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        if (std::holds_alternative<ShakerCoil>(attachments_[i].model)) {
            coil_ = static_cast<int>(i);
        }
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
    if (shaker_) force_per_volt_ = blocked_force_per_volt(*shaker_, frequency_hz);
    for (auto& a : attachments_) bench::set_frequency(a, frequency_hz);

    SpecimenState kept;
    const bool had_state = structure_ != nullptr;
    if (had_state) {
        kept.q = structure_->q();
        kept.q_dot = structure_->q_dot();
    }
    structure_ =
        std::make_unique<structure::ReducedModalModel>(active_model(), active_basis(), dt_s_);
    attachment_point_index_.clear();
    loaded_points_.clear();
    const auto add_loaded = [this](int index) {
        if (std::find(loaded_points_.begin(), loaded_points_.end(), index) ==
            loaded_points_.end()) {
            loaded_points_.push_back(index);
        }
    };
    for (const auto& a : attachments_) {
        attachment_point_index_.push_back(structure_->point_index(a.point));
        add_loaded(attachment_point_index_.back());
    }
    for (std::size_t c = 0; c < channels_.size(); ++c) {
        if (channels_[c].quantity != RecordedChannel::Quantity::damper_force) {
            channel_index_[c] = structure_->point_index(channels_[c].point);
        }
    }
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        shaker_index_ = structure_->point_index(excitation_.point);
        add_loaded(shaker_index_);
    }
    point_totals_.assign(loaded_points_.size(), Eigen::Matrix<double, 6, 1>::Zero());
    if (had_state) {
        // A point starts at phase 0 of its own sine (whole periods before it end there too),
        // so the excitation is continuous across the frequency change.
        set_loads(0.0, 0.0);
        structure_->set_state(kept.q, kept.q_dot, 0.0);
    }
}

double CoupledSpecimen::excitation_value(double amplitude, double time_s) const {
    if (waveform_) return amplitude * waveform_(waveform_offset_s_ + time_s);
    return amplitude * std::sin(hz_to_rad_s(frequency_hz_) * time_s);
}

void CoupledSpecimen::set_waveform(std::function<double(double)> waveform, double offset_s) {
    if (waveform && (shaker_ || excitation_.kind != structure::ExcitationSpec::Kind::force)) {
        throw std::logic_error("coupled specimen: a waveform drives a force excitation only");
    }
    waveform_ = std::move(waveform);
    waveform_offset_s_ = offset_s;
}

double CoupledSpecimen::drive_force(double amplitude, double time_s) const {
    if (!shaker_) return excitation_value(amplitude, time_s);
    // The voltage's share of the coil current in its steady state: |G| V sin(w t + arg G).
    // Its transient after an amplitude change lasts the coil's L / R, microseconds to a
    // millisecond against periods of tens of milliseconds, and is left out.
    return std::abs(force_per_volt_) * amplitude *
           std::sin(hz_to_rad_s(frequency_hz_) * time_s + std::arg(force_per_volt_));
}

void CoupledSpecimen::set_loads(double amplitude, double time_s) {
    // Every load at a point adds up: several attachments, and the shaker's force where an
    // attachment sits at the shaker point (set one by one, each would replace the other).
    for (auto& total : point_totals_) total.setZero();
    const auto slot = [this](int point) {
        return static_cast<std::size_t>(
            std::find(loaded_points_.begin(), loaded_points_.end(), point) -
            loaded_points_.begin());
    };
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        point_totals_[slot(attachment_point_index_[i])] += loads_[i];
    }
    const double value = excitation_value(amplitude, time_s);
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        point_totals_[slot(shaker_index_)].head<3>() += drive_force(amplitude, time_s) * direction_;
    } else {
        const double w = hz_to_rad_s(frequency_hz_);
        const double phase = w * time_s;
        // a = A sin(wt): v = -A/w cos(wt), d = -A/w^2 sin(wt) (zero-mean harmonic motion).
        structure_->set_base_motion(-amplitude / (w * w) * std::sin(phase),
                                    -amplitude / w * std::cos(phase), value);
    }
    for (std::size_t k = 0; k < loaded_points_.size(); ++k) {
        structure_->set_point_load(loaded_points_[k], point_totals_[k].head<3>(),
                                   point_totals_[k].tail<3>());
    }
}

void CoupledSpecimen::start_from_linear_steady_state(double amplitude, double time_s,
                                                     std::complex<double> response_ratio) {
    if (!structure_) {
        throw std::logic_error("coupled specimen: set_frequency before starting");
    }
    // The enclosures jump with the structure: the particles go with them, keeping their
    // positions and velocities relative to their enclosure.
    std::vector<AttachmentState> kept;
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        kept.push_back(state_at(attachments_[i], point_motion(i)));
    }
    // The start model's steady state in physical DOFs, x = Phi_s q_s, projected on the
    // specimen's mass-normalised modes: q = Phi^T M x (both models share their free DOFs).
    structure::ReducedModalModel start(*start_model_, *start_basis_, dt_s_);
    if (excitation_.kind == structure::ExcitationSpec::Kind::force) {
        // Through a shaker, the blocked force |G| V sin(w (t + arg G / w)).
        const double w = hz_to_rad_s(frequency_hz_);
        const double force = shaker_ ? std::abs(force_per_volt_) * amplitude : amplitude;
        const double lead_s = shaker_ ? std::arg(force_per_volt_) / w : 0.0;
        start.set_harmonic_steady_state(excitation_.point, direction_, force, frequency_hz_,
                                        time_s + lead_s);
    } else {
        start.set_harmonic_base_steady_state(amplitude, frequency_hz_, time_s);
        structure_->set_harmonic_base_steady_state(amplitude, frequency_hz_, time_s);
    }
    const int start_modes = start.modes();
    const structure::LinearModel& model = active_model();
    const structure::ModalBasis& basis = active_basis();
    const Eigen::MatrixXd projection = basis.shapes.leftCols(structure_->modes()).transpose() *
                                       model.mass() * start_basis_->shapes.leftCols(start_modes);
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
    // Static deflection under the attachments' weight at rest on their walls, so that the
    // weight does not start a transient: q_s = phi^T f_w / omega^2.
    Eigen::VectorXd q = q_linear;
    const int modes = structure_->modes();
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        const PointLoad w = weight(attachments_[i]);
        const Eigen::VectorXd f = model.point_load(attachments_[i].point, w.force_n, w.moment_nm);
        for (int m = 0; m < modes; ++m) {
            const double omega = basis.modes[static_cast<std::size_t>(m)].frequency_hz * kTwoPi;
            q[m] += basis.shapes.col(m).dot(f) / (omega * omega);
        }
        loads_[i] << w.force_n, w.moment_nm;
    }
    set_loads(amplitude, time_s);
    structure_->set_state(q, q_dot_linear, time_s);
    carry_attachments(kept);
}

void CoupledSpecimen::step(double amplitude, std::vector<double>& values) {
    const double dt = dt_s_;
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        const PointLoad load = bench::step(attachments_[i], point_motion(i), dt);
        next_loads_[i] << load.force_n, load.moment_nm;
    }
    // A lock released particles in this step: the structure no longer carries them from its
    // start on, with the loads at the start as they were.
    if (held_changed()) rebuild_structure(true, amplitude);
    std::swap(loads_, next_loads_);
    const double t_next = structure_->time_s() + dt;
    set_loads(amplitude, t_next);
    structure_->step();

    values.resize(names_.size());
    values[0] = excitation_value(amplitude, structure_->time_s());
    for (std::size_t c = 0; c < channels_.size(); ++c) {
        const int k = channel_index_[c];
        const Eigen::Vector3d& along = channels_[c].direction;
        switch (channels_[c].quantity) {
            case RecordedChannel::Quantity::acceleration:
                values[c + 1] = structure_->acceleration(k).dot(along);
                break;
            case RecordedChannel::Quantity::velocity:
                values[c + 1] = structure_->velocity(k).dot(along);
                break;
            case RecordedChannel::Quantity::displacement:
                values[c + 1] = structure_->displacement(k).dot(along);
                break;
            case RecordedChannel::Quantity::damper_force: {
                // The force the damper applied to the structure over the step just taken,
                // with the inertia of the particles its lock holds, which the structure's
                // mass carries when they are held in it: -m (a + alpha x r) at their centre
                // (the centripetal term is second order in the rotation).
                const auto i = static_cast<std::size_t>(k);
                const HeldBody& held = held_bodies_[i];
                Eigen::Vector3d force = loads_[i].head<3>();
                if (held.mass_kg > 0.0) {
                    const int p = attachment_point_index_[i];
                    force -=
                        held.mass_kg * (structure_->acceleration(p) +
                                        structure_->angular_acceleration(p).cross(held.centre_m));
                }
                values[c + 1] = force.dot(along);
                break;
            }
        }
    }
    if (shaker_) {
        // The transducer at the stinger's end: the coil's force less the suspension's and the
        // armature's inertia, which stay on the shaker's side.
        double force = drive_force(amplitude, structure_->time_s());
        if (coil_ >= 0) {
            force += loads_[static_cast<std::size_t>(coil_)].head<3>().dot(direction_);
        }
        force -=
            shaker_->armature_mass_kg * structure_->acceleration(shaker_index_).dot(direction_);
        values.back() = force;
    }
}

PointMotion CoupledSpecimen::point_motion(std::size_t attachment) const {
    const int p = attachment_point_index_[attachment];
    PointMotion m;
    m.position_m =
        model_->point(attachments_[attachment].point).position_m + structure_->displacement(p);
    m.rotation = rotation_of(structure_->rotation(p));
    m.velocity_m_s = structure_->velocity(p);
    m.angular_velocity_rad_s = structure_->angular_velocity(p);
    m.acceleration_m_s2 = structure_->acceleration(p);
    return m;
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
    // The beds ride with their enclosures through the jump: same enclosure-frame positions,
    // relative velocities and contact histories, as between two points (restore()), so the
    // jump itself starts no impacts.
    std::vector<AttachmentState> kept;
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        kept.push_back(state_at(attachments_[i], point_motion(i)));
    }
    structure_->set_state(scaled, scaled_rate, structure_->time_s());
    carry_attachments(kept);
}

SpecimenState CoupledSpecimen::state() const {
    SpecimenState s;
    s.q = structure_->q();
    s.q_dot = structure_->q_dot();
    s.loads = loads_;
    for (const auto& a : attachments_) s.attachments.push_back(bench::state(a));
    return s;
}

void CoupledSpecimen::restore(const SpecimenState& state) {
    if (!structure_) {
        throw std::logic_error("coupled specimen: set_frequency before restoring");
    }
    if (state.attachments.size() != attachments_.size() ||
        state.loads.size() != attachments_.size()) {
        throw std::invalid_argument(
            "coupled specimen: state has " + std::to_string(state.attachments.size()) +
            " attachments, the specimen " + std::to_string(attachments_.size()));
    }
    // The attachments first: their locks say which model the saved modal state belongs to.
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        bench::restore(attachments_[i], state.attachments[i]);
    }
    if (held_changed()) rebuild_structure(false, 0.0);
    loads_ = state.loads;
    set_loads(0.0, 0.0);
    structure_->set_state(state.q, state.q_dot, 0.0);
}

void CoupledSpecimen::carry_held_particles() {
    if (structure_) {
        throw std::logic_error("coupled specimen: carry the held particles before set_frequency");
    }
    carry_held_ = true;
    for (auto& a : attachments_) {
        if (auto* dem = std::get_if<DemDamper>(&a.model)) dem->carry_held_inertia_in_structure();
    }
    build_held_model();
}

const structure::LinearModel& CoupledSpecimen::active_model() const {
    return held_model_ ? *held_model_ : *model_;
}

const structure::ModalBasis& CoupledSpecimen::active_basis() const {
    return held_basis_ ? *held_basis_ : *basis_;
}

bool CoupledSpecimen::held_changed() const {
    if (!carry_held_) return false;
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        const dem::Solver* solver = dem_solver(attachments_[i]);
        if ((solver ? solver->locked_count() : 0) != held_counts_[i]) return true;
    }
    return false;
}

void CoupledSpecimen::build_held_model() {
    held_model_.reset();
    held_basis_.reset();
    std::fill(held_counts_.begin(), held_counts_.end(), 0);
    std::fill(held_bodies_.begin(), held_bodies_.end(), HeldBody{});
    const auto holds = [](const Attachment& a) {
        const dem::Solver* solver = dem_solver(a);
        return solver && solver->locked_count() > 0;
    };
    // Nothing held (every sweep without a lock, every one after its release): the structure's
    // own model, not a copy of it.
    if (std::none_of(attachments_.begin(), attachments_.end(), holds)) return;
    structure::LinearModel held = *model_;
    if (!held.damping()) {
        // The held particles add mass, not damping: the structure keeps its own damping
        // matrix, C = M Phi diag(2 zeta_r w_r) Phi^T M over its modes (mass-normalised,
        // Phi^T C Phi = diag(2 zeta_r w_r)), and the held model's ratios follow from it
        // (compute_modes: zeta = phi^T C phi / 2 w), lower than the structure's by about
        // sqrt(m / (m + m_held)) on a mode the bed loads.
        const Eigen::MatrixXd m_phi = model_->mass() * basis_->shapes;
        Eigen::VectorXd modal(static_cast<Eigen::Index>(basis_->modes.size()));
        for (std::size_t r = 0; r < basis_->modes.size(); ++r) {
            const auto& mode = basis_->modes[r];
            modal(static_cast<Eigen::Index>(r)) =
                2.0 * mode.damping_ratio * kTwoPi * mode.frequency_hz;
        }
        held.set_damping(m_phi * modal.asDiagonal() * m_phi.transpose());
    }
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        const auto* dem = std::get_if<DemDamper>(&attachments_[i].model);
        if (!dem || !holds(attachments_[i])) continue;
        held_counts_[i] = dem->solver().locked_count();
        const HeldBody& body = held_bodies_[i] = dem->held_body();
        held.add_rigid_body(
            attachments_[i].point,
            structure::rigid_body_mass(body.mass_kg, body.inertia_kg_m2, body.centre_m));
    }
    // The damping matrix gives the ratios; the spec is not read.
    held_basis_ = structure::compute_modes(held, structure::DampingSpec{},
                                           static_cast<int>(basis_->modes.size()));
    held_model_ = std::move(held);
}

void CoupledSpecimen::rebuild_structure(bool project, double amplitude) {
    Eigen::VectorXd x, v;
    double time_s = 0.0;
    if (project) {
        const Eigen::MatrixXd shapes = active_basis().shapes.leftCols(structure_->modes());
        x = shapes * structure_->q();
        v = shapes * structure_->q_dot();
        time_s = structure_->time_s();
    }
    build_held_model();
    structure_ =
        std::make_unique<structure::ReducedModalModel>(active_model(), active_basis(), dt_s_);
    if (!project) return;
    // Mass-normalised modes: q' = Phi'^T M' x is the M'-orthogonal projection of x on the new
    // modes, exact when they span it (a truncated basis keeps the part they span).
    const Eigen::MatrixXd to_modes =
        active_basis().shapes.leftCols(structure_->modes()).transpose() * active_model().mass();
    set_loads(amplitude, time_s);
    structure_->set_state(to_modes * x, to_modes * v, time_s);
}

void CoupledSpecimen::carry_attachments(const std::vector<AttachmentState>& states) {
    for (std::size_t i = 0; i < attachments_.size(); ++i) {
        bench::restore_at(attachments_[i], states[i], point_motion(i));
    }
}

}  // namespace sb::bench

// Time stepping of the first modes with an exact discretisation, O(modes) per step.
#include "structure/reduced_modal_model.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::structure {

ReducedModalModel::ReducedModalModel(const LinearModel& model, const ModalBasis& basis, double dt_s,
                                     int modes)
    : dt_(dt_s) {
    if (!(dt_s > 0.0)) throw std::invalid_argument("ReducedModalModel: dt must be > 0");
    const int available = static_cast<int>(basis.modes.size());
    const int kept = modes < 0 ? available : std::min(modes, available);
    if (kept < 1) throw std::invalid_argument("ReducedModalModel: no modes");
    omega_ = circular_frequencies(basis).head(kept);
    zeta_ = damping_ratios(basis).head(kept);
    for (int r = 0; r < kept; ++r) steps_.push_back(oscillator_step(omega_(r), zeta_(r), dt_));
    const Eigen::MatrixXd phi = basis.shapes.leftCols(kept);
    participation_ = Eigen::VectorXd::Zero(kept);
    if (model.base_influence()) {
        participation_ = phi.transpose() * (model.mass() * *model.base_influence());
    }
    for (const auto& name : model.point_names()) {
        const auto& op = model.point(name).op;
        names_.push_back(name);
        rows_.emplace_back(op * phi);
        base_rows_.emplace_back(model.point(name).base_motion);
    }
    point_loads_.assign(names_.size(), Eigen::Matrix<double, 6, 1>::Zero());
    loaded_.assign(names_.size(), false);
    q_ = qd_ = qdd_ = load_start_ = load_end_ = Eigen::VectorXd::Zero(kept);
}

int ReducedModalModel::point_index(std::string_view name) const {
    for (std::size_t i = 0; i < names_.size(); ++i) {
        if (names_[i] == name) return static_cast<int>(i);
    }
    throw std::out_of_range("unknown point '" + std::string(name) + "'");
}

void ReducedModalModel::clear_loads() {
    for (auto& l : point_loads_) l.setZero();
    loaded_.assign(names_.size(), false);
    base_acceleration_ = 0.0;
}

void ReducedModalModel::set_point_load(std::string_view point, const Eigen::Vector3d& force_n,
                                       const Eigen::Vector3d& moment_nm) {
    set_point_load(point_index(point), force_n, moment_nm);
}

void ReducedModalModel::set_point_load(int point, const Eigen::Vector3d& force_n,
                                       const Eigen::Vector3d& moment_nm) {
    const auto i = static_cast<std::size_t>(point);
    point_loads_.at(i) << force_n, moment_nm;
    loaded_[i] = true;
}

void ReducedModalModel::set_base_acceleration(double acceleration_m_s2) {
    base_acceleration_ = acceleration_m_s2;
}

void ReducedModalModel::set_base_motion(double displacement_m, double velocity_m_s,
                                        double acceleration_m_s2) {
    base_displacement_ = displacement_m;
    base_velocity_ = velocity_m_s;
    base_acceleration_ = acceleration_m_s2;
}

void ReducedModalModel::modal_load_into(Eigen::VectorXd& out) const {
    // Relative coordinates under base motion: M y'' + C y' + K y = f - M r a_b
    // (Chopra, Dynamics of Structures, eq. 9.4.9), projected on the modes.
    out = -base_acceleration_ * participation_;
    for (std::size_t i = 0; i < names_.size(); ++i) {
        if (loaded_[i]) out.noalias() += rows_[i].transpose() * point_loads_[i];
    }
}

void ReducedModalModel::update_acceleration() {
    // Equation of motion at the current time: q'' = f - 2 zeta w q' - w^2 q.
    qdd_ = load_start_.array() - 2.0 * zeta_.array() * omega_.array() * qd_.array() -
           omega_.array().square() * q_.array();
}

void ReducedModalModel::step() {
    modal_load_into(load_end_);
    for (int r = 0; r < modes(); ++r) {
        const auto& s = steps_[static_cast<std::size_t>(r)];
        const Eigen::Vector2d x(q_(r), qd_(r));
        const Eigen::Vector2d next =
            s.phi * x + s.gamma0 * load_start_(r) + s.gamma1 * (load_end_(r) - load_start_(r));
        q_(r) = next(0);
        qd_(r) = next(1);
    }
    load_start_.swap(load_end_);
    time_ += dt_;
    update_acceleration();
}

Eigen::Vector3d ReducedModalModel::displacement(std::string_view point) const {
    return displacement(point_index(point));
}
Eigen::Vector3d ReducedModalModel::displacement(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].topRows<3>() * q_ + base_rows_[i].head<3>() * base_displacement_;
}
Eigen::Vector3d ReducedModalModel::velocity(std::string_view point) const {
    return velocity(point_index(point));
}
Eigen::Vector3d ReducedModalModel::velocity(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].topRows<3>() * qd_ + base_rows_[i].head<3>() * base_velocity_;
}
Eigen::Vector3d ReducedModalModel::acceleration(std::string_view point) const {
    return acceleration(point_index(point));
}
Eigen::Vector3d ReducedModalModel::acceleration(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].topRows<3>() * qdd_ + base_rows_[i].head<3>() * base_acceleration_;
}
Eigen::Vector3d ReducedModalModel::rotation(std::string_view point) const {
    return rotation(point_index(point));
}
Eigen::Vector3d ReducedModalModel::rotation(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].bottomRows<3>() * q_ + base_rows_[i].tail<3>() * base_displacement_;
}
Eigen::Vector3d ReducedModalModel::angular_velocity(std::string_view point) const {
    return angular_velocity(point_index(point));
}
Eigen::Vector3d ReducedModalModel::angular_velocity(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].bottomRows<3>() * qd_ + base_rows_[i].tail<3>() * base_velocity_;
}
Eigen::Vector3d ReducedModalModel::angular_acceleration(int point) const {
    const auto i = static_cast<std::size_t>(point);
    return rows_[i].bottomRows<3>() * qdd_ + base_rows_[i].tail<3>() * base_acceleration_;
}

void ReducedModalModel::set_steady_state(const Eigen::VectorXcd& modal_load_phasor,
                                         double omega_rad_s, double time_s) {
    using namespace std::complex_literals;
    const std::complex<double> rotor = std::exp(1i * (omega_rad_s * time_s));
    for (int r = 0; r < modes(); ++r) {
        // Steady-state receptance of a modal oscillator: 1 / (w_r^2 - W^2 + 2 i zeta_r w_r W)
        // (Ewins, Modal Testing, eq. 2.52).
        const std::complex<double> h = 1.0 / (omega_(r) * omega_(r) - omega_rad_s * omega_rad_s +
                                              2i * zeta_(r) * omega_(r) * omega_rad_s);
        const std::complex<double> q = h * modal_load_phasor(r) * rotor;
        q_(r) = q.real();
        qd_(r) = (1i * omega_rad_s * q).real();
        load_start_(r) = (modal_load_phasor(r) * rotor).real();
    }
    time_ = time_s;
    update_acceleration();
}

void ReducedModalModel::set_harmonic_steady_state(std::string_view point,
                                                  const Eigen::Vector3d& direction,
                                                  double force_amplitude_n, double frequency_hz,
                                                  double time_s) {
    using namespace std::complex_literals;
    const int index = point_index(point);
    const Eigen::Vector3d unit = direction.normalized();
    // F sin(W t) = Re(-i F e^{i W t}).
    const Eigen::VectorXd modal =
        rows_[static_cast<std::size_t>(index)].topRows<3>().transpose() * unit * force_amplitude_n;
    const double omega = kTwoPi * frequency_hz;
    set_steady_state(modal.cast<std::complex<double>>() * (-1i), omega, time_s);
    // Keep the stored load consistent with the start-of-step load.
    set_point_load(index, unit * (force_amplitude_n * std::sin(omega * time_s)),
                   Eigen::Vector3d::Zero());
    base_displacement_ = base_velocity_ = base_acceleration_ = 0.0;
}

void ReducedModalModel::set_harmonic_base_steady_state(double acceleration_amplitude_m_s2,
                                                       double frequency_hz, double time_s) {
    using namespace std::complex_literals;
    const double omega = kTwoPi * frequency_hz;
    // a_b = A sin(W t) = Re(-i A e^{i W t}); modal load -Gamma a_b.
    const Eigen::VectorXcd phasor =
        participation_.cast<std::complex<double>>() * (1i * acceleration_amplitude_m_s2);
    set_steady_state(phasor, omega, time_s);
    const double phase = omega * time_s;
    base_acceleration_ = acceleration_amplitude_m_s2 * std::sin(phase);
    base_velocity_ = -acceleration_amplitude_m_s2 / omega * std::cos(phase);
    base_displacement_ = -acceleration_amplitude_m_s2 / (omega * omega) * std::sin(phase);
}

void ReducedModalModel::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& q_dot,
                                  double time_s) {
    if (q.size() != modes() || q_dot.size() != modes()) {
        throw std::invalid_argument("ReducedModalModel::set_state: wrong number of modes");
    }
    q_ = q;
    qd_ = q_dot;
    time_ = time_s;
    modal_load_into(load_start_);
    update_acceleration();
}

}  // namespace sb::structure

// Implicit Newmark (average acceleration) integration of the full finite element model.
#include "structure/newmark_integrator.hpp"

#include <Eigen/LU>
#include <complex>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::structure {
namespace {
constexpr double kBeta = 0.25;
constexpr double kGamma = 0.5;
}  // namespace

Eigen::MatrixXd damping_matrix(const LinearModel& model, const ModalBasis& basis,
                               const DampingSpec& damping) {
    if (model.damping()) return *model.damping();
    if (damping.model == DampingSpec::Model::rayleigh) {
        return damping.alpha_per_s * model.mass() + damping.beta_s * model.stiffness();
    }
    const Eigen::VectorXd c_modal =
        2.0 * damping_ratios(basis).array() * circular_frequencies(basis).array();
    const Eigen::MatrixXd m_phi = model.mass() * basis.shapes;
    return m_phi * c_modal.asDiagonal() * m_phi.transpose();
}

NewmarkIntegrator::NewmarkIntegrator(const LinearModel& model, const ModalBasis& basis,
                                     const DampingSpec& damping, double dt_s)
    : model_(&model), dt_(dt_s), c_(damping_matrix(model, basis, damping)) {
    if (!(dt_s > 0.0)) throw std::invalid_argument("NewmarkIntegrator: dt must be > 0");
    const double h = dt_;
    effective_.compute(model.stiffness() + kGamma / (kBeta * h) * c_ +
                       1.0 / (kBeta * h * h) * model.mass());
    const int n = model.dofs();
    x_ = v_ = a_ = point_load_sum_ = Eigen::VectorXd::Zero(n);
}

void NewmarkIntegrator::clear_loads() {
    point_loads_.clear();
    point_load_sum_.setZero();
    base_acceleration_ = 0.0;
}

void NewmarkIntegrator::set_point_load(std::string_view point, const Eigen::Vector3d& force_n,
                                       const Eigen::Vector3d& moment_nm) {
    Eigen::VectorXd f = model_->point_load(point, force_n, moment_nm);
    for (auto& [name, load] : point_loads_) {
        if (name == point) {
            point_load_sum_ += f - load;
            load = std::move(f);
            return;
        }
    }
    point_load_sum_ += f;
    point_loads_.emplace_back(std::string(point), std::move(f));
}

void NewmarkIntegrator::set_base_acceleration(double acceleration_m_s2) {
    if (!model_->base_influence()) {
        throw std::logic_error("NewmarkIntegrator: the model has no base excitation");
    }
    base_acceleration_ = acceleration_m_s2;
}

void NewmarkIntegrator::set_base_motion(double displacement_m, double velocity_m_s,
                                        double acceleration_m_s2) {
    set_base_acceleration(acceleration_m_s2);
    base_displacement_ = displacement_m;
    base_velocity_ = velocity_m_s;
}

Eigen::Matrix<double, 6, 1> NewmarkIntegrator::base_motion_of(std::string_view point) const {
    return model_->point(point).base_motion;
}

Eigen::VectorXd NewmarkIntegrator::current_load() const {
    Eigen::VectorXd f = point_load_sum_;
    if (model_->base_influence()) {
        f -= model_->mass() * (*model_->base_influence() * base_acceleration_);
    }
    return f;
}

void NewmarkIntegrator::step() {
    // Newmark's method in effective-stiffness form (Bathe, Finite Element Procedures,
    // Table 9.3 with delta = gamma, alpha = beta).
    const double h = dt_;
    const double a0 = 1.0 / (kBeta * h * h);
    const double a1 = kGamma / (kBeta * h);
    const double a2 = 1.0 / (kBeta * h);
    const double a3 = 1.0 / (2.0 * kBeta) - 1.0;
    const double a4 = kGamma / kBeta - 1.0;
    const double a5 = h / 2.0 * (kGamma / kBeta - 2.0);
    const Eigen::VectorXd rhs = current_load() + model_->mass() * (a0 * x_ + a2 * v_ + a3 * a_) +
                                c_ * (a1 * x_ + a4 * v_ + a5 * a_);
    const Eigen::VectorXd x_next = effective_.solve(rhs);
    const Eigen::VectorXd a_next = a0 * (x_next - x_) - a2 * v_ - a3 * a_;
    v_ += h * ((1.0 - kGamma) * a_ + kGamma * a_next);
    a_ = a_next;
    x_ = x_next;
    time_ += h;
}

Eigen::Vector3d NewmarkIntegrator::displacement(std::string_view point) const {
    return model_->point(point).op.topRows<3>() * x_ +
           base_motion_of(point).head<3>() * base_displacement_;
}
Eigen::Vector3d NewmarkIntegrator::velocity(std::string_view point) const {
    return model_->point(point).op.topRows<3>() * v_ +
           base_motion_of(point).head<3>() * base_velocity_;
}
Eigen::Vector3d NewmarkIntegrator::acceleration(std::string_view point) const {
    return model_->point(point).op.topRows<3>() * a_ +
           base_motion_of(point).head<3>() * base_acceleration_;
}
Eigen::Vector3d NewmarkIntegrator::rotation(std::string_view point) const {
    return model_->point(point).op.bottomRows<3>() * x_ +
           base_motion_of(point).tail<3>() * base_displacement_;
}
Eigen::Vector3d NewmarkIntegrator::angular_velocity(std::string_view point) const {
    return model_->point(point).op.bottomRows<3>() * v_ +
           base_motion_of(point).tail<3>() * base_velocity_;
}

void NewmarkIntegrator::set_harmonic_steady_state(std::string_view point,
                                                  const Eigen::Vector3d& direction,
                                                  double force_amplitude_n, double frequency_hz,
                                                  double time_s) {
    using namespace std::complex_literals;
    const Eigen::Vector3d unit = direction.normalized();
    const double w = kTwoPi * frequency_hz;
    // F sin(W t) = Re(-i F e^{i W t}); X = (K - W^2 M + i W C)^-1 F_hat.
    const Eigen::VectorXcd f_hat =
        model_->point_load(point, unit * force_amplitude_n, Eigen::Vector3d::Zero())
            .cast<std::complex<double>>() *
        (-1i);
    const Eigen::MatrixXcd dynamic =
        (model_->stiffness() - w * w * model_->mass()).cast<std::complex<double>>() +
        (1i * w) * c_.cast<std::complex<double>>();
    const Eigen::VectorXcd x_hat = dynamic.partialPivLu().solve(f_hat);
    const std::complex<double> rotor = std::exp(1i * (w * time_s));
    x_ = (x_hat * rotor).real();
    v_ = (x_hat * (1i * w) * rotor).real();
    a_ = (x_hat * (-w * w) * rotor).real();
    time_ = time_s;
    set_point_load(point, unit * (force_amplitude_n * std::sin(w * time_s)),
                   Eigen::Vector3d::Zero());
}

}  // namespace sb::structure

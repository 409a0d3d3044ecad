// Residual of other modes: one mode plus residual flexibility and mass line, by variable
// projection (Golub & Pereyra, SIAM J. Numer. Anal. 10, 1973) and Levenberg–Marquardt.
#include "identification/residual.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unsupported/Eigen/LevenbergMarquardt>
#include <unsupported/Eigen/NumericalDiff>
#include <vector>

#include "core/units.hpp"

namespace sb::identification {

namespace {

/// Fewest points of the fit: 2 nonlinear and 3 complex linear unknowns (8 real) need 4
/// complex points; one more leaves a check.
constexpr int kMinPoints = 5;

/// Normalised data: q = ω/ω_ref, t = mobility/|mobility|max.
struct Points {
    std::vector<double> q;
    std::vector<std::complex<double>> t;
};

/// Columns (mobility, normalised): mode iq/(qn² − q² + 2iζqn q), residual flexibility iq,
/// mass line iq/q².
Eigen::MatrixXcd basis(const Points& p, double qn, double zeta) {
    const auto m = static_cast<Eigen::Index>(p.q.size());
    Eigen::MatrixXcd a(m, 3);
    for (Eigen::Index r = 0; r < m; ++r) {
        const double q = p.q[static_cast<std::size_t>(r)];
        const std::complex<double> iq(0.0, q);
        a(r, 0) = iq / std::complex<double>(qn * qn - q * q, 2.0 * zeta * qn * q);
        a(r, 1) = iq;
        a(r, 2) = iq / (q * q);
    }
    return a;
}

Eigen::VectorXcd data(const Points& p) {
    Eigen::VectorXcd b(static_cast<Eigen::Index>(p.t.size()));
    for (std::size_t r = 0; r < p.t.size(); ++r) b(static_cast<Eigen::Index>(r)) = p.t[r];
    return b;
}

/// Misfit of the best linear combination for x = (ln qn, ln ζ): real and imaginary parts.
struct Projection : Eigen::DenseFunctor<double> {
    const Points* points;
    explicit Projection(const Points& p)
        : Eigen::DenseFunctor<double>(2, 2 * static_cast<int>(p.q.size())), points(&p) {}
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
        const Eigen::MatrixXcd a = basis(*points, std::exp(x(0)), std::exp(x(1)));
        const Eigen::VectorXcd b = data(*points);
        const Eigen::VectorXcd r = b - a * a.colPivHouseholderQr().solve(b);
        for (Eigen::Index i = 0; i < r.size(); ++i) {
            f(2 * i) = r(i).real();
            f(2 * i + 1) = r(i).imag();
        }
        return 0;
    }
};

}  // namespace

ResidualFit fit_residual(const Frf& frf, double start_frequency_hz, double start_damping_ratio,
                         double min_relative_magnitude) {
    ResidualFit fit;
    const Frf mob = convert(frf, FrfForm::mobility);
    const std::size_t n = mob.value.size();
    if (n == 0 || !(start_frequency_hz > 0.0) || !(start_damping_ratio > 0.0)) {
        fit.message = "no start for the residual fit";
        return fit;
    }
    std::size_t peak = 0;
    for (std::size_t i = 1; i < n; ++i) {
        if (std::abs(mob.value[i]) > std::abs(mob.value[peak])) peak = i;
    }
    const double t_max = std::abs(mob.value[peak]);
    const double level = min_relative_magnitude * t_max;
    std::size_t lo = peak;
    while (lo > 0 && std::abs(mob.value[lo - 1]) >= level) --lo;
    std::size_t hi = peak;
    while (hi + 1 < n && std::abs(mob.value[hi + 1]) >= level) ++hi;
    fit.points_used = static_cast<int>(hi - lo + 1);
    if (fit.points_used < kMinPoints) {
        fit.message = std::to_string(fit.points_used) + " point(s) for the residual fit; need " +
                      std::to_string(kMinPoints);
        return fit;
    }
    const double w_ref = hz_to_rad_s(start_frequency_hz);
    Points p;
    for (std::size_t i = lo; i <= hi; ++i) {
        p.q.push_back(hz_to_rad_s(mob.frequency_hz[i]) / w_ref);
        p.t.push_back(mob.value[i] / t_max);
    }
    Projection projection(p);
    Eigen::NumericalDiff<Projection> numerical(projection);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<Projection>> lm(numerical);
    lm.setXtol(1e-13);
    lm.setFtol(1e-15);
    lm.setMaxfev(2000);
    Eigen::VectorXd x(2);
    x << 0.0, std::log(start_damping_ratio);
    lm.minimize(x);
    const double qn = std::exp(x(0));
    const double zeta = std::exp(x(1));
    if (!std::isfinite(qn) || !(qn > p.q.front() && qn < p.q.back()) || !(zeta < 1.0)) {
        fit.message = "the mode-plus-residual fit has no resonance inside its points";
        return fit;
    }
    const Eigen::VectorXcd c = basis(p, qn, zeta).colPivHouseholderQr().solve(data(p));
    // Back to receptance: mobility = iω α, and the columns were scaled by ω_ref and |T|max.
    const double wn = qn * w_ref;
    fit.ok = true;
    fit.natural_frequency_hz = wn / kTwoPi;
    fit.damping_ratio = zeta;
    fit.modal_constant = c(0) * t_max * w_ref;
    fit.stiffness_term = c(1) * t_max / w_ref;
    fit.mass_term = c(2) * t_max / w_ref / (qn * qn);  // coefficient of (ωn/ω)²
    const double response = std::abs(fit.modal_constant) / (2.0 * zeta * wn * wn);
    fit.residual_ratio = std::abs(fit.stiffness_term + fit.mass_term) / response;
    return fit;
}

Frf subtract_residual(const Frf& frf, const ResidualFit& fit) {
    Frf out = frf;
    const int k = form_order(frf.form);
    const double wn = hz_to_rad_s(fit.natural_frequency_hz);
    for (std::size_t i = 0; i < out.value.size(); ++i) {
        const double w = hz_to_rad_s(out.frequency_hz[i]);
        const std::complex<double> residual =
            fit.stiffness_term + fit.mass_term * (wn / w) * (wn / w);
        out.value[i] -= std::pow(std::complex<double>(0.0, w), k) * residual;
    }
    return out;
}

ModalEstimate estimate_with_residual(const Frf& frf, const ResidualOptions& options,
                                     const std::function<ModalEstimate(const Frf&)>& estimate,
                                     const std::function<ModalEstimate(const Frf&)>& start) {
    ModalEstimate raw = estimate(frf);
    if (!options.compensate) return raw;
    const ModalEstimate from = raw.ok() ? raw : start(frf);
    if (!from.ok()) return raw;
    const ResidualFit fit = fit_residual(frf, from.natural_frequency_hz, from.damping_ratio,
                                         options.min_relative_magnitude);
    if (!fit.ok) return raw;
    if (fit.residual_ratio > options.max_residual_ratio) {
        std::ostringstream s;
        s.precision(3);
        s << "the residual of other modes at " << fit.natural_frequency_hz << " Hz is "
          << fit.residual_ratio << " times this mode's response (limit "
          << options.max_residual_ratio << "): the modes are not well separated";
        return failed_estimate(EstimateStatus::residual_dominates, s.str());
    }
    ModalEstimate e = estimate(subtract_residual(frf, fit));
    e.residual_ratio = fit.residual_ratio;
    return e;
}

}  // namespace sb::identification

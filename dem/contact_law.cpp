// Contact law composition and the restitution-to-damping relations.
#include "dem/contact_law.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "core/units.hpp"

namespace sb::dem {

std::string ContactLaw::describe() const {
    std::string s = "normal=";
    s += std::visit([](const auto& p) { return std::string(p.kName); }, normal);
    s += " damping=";
    s += std::visit([](const auto& p) { return std::string(p.kName); }, damping);
    s += " tangential=";
    s += std::visit([](const auto& p) { return std::string(p.kName); }, tangential);
    s += " rolling=";
    s += std::visit([](const auto& p) { return std::string(p.kName); }, rolling);
    return s;
}

ContactLaw make_contact_law(const ContactOptions& o) {
    ContactLaw law;
    if (o.normal == NormalLaw::hooke) {
        law.normal = Hooke{};
    } else {
        law.normal = Hertz{};
    }
    switch (o.damping) {
        case DampingLaw::none:
            law.damping = NoDamping{};
            break;
        case DampingLaw::linear_dashpot:
            law.damping = LinearDashpot{};
            break;
        case DampingLaw::hertz_dashpot:
            law.damping = HertzDashpot{};
            break;
        case DampingLaw::viscoelastic:
            law.damping = Viscoelastic{};
            break;
        case DampingLaw::viscous:
            law.damping = ViscousDashpot{};
            break;
        case DampingLaw::restitution:
            if (o.normal == NormalLaw::hooke) {
                law.damping = LinearDashpot{};
            } else {
                law.damping = HertzDashpot{};
            }
            break;
    }
    switch (o.tangential) {
        case TangentialLaw::none:
            law.tangential = NoFriction{};
            break;
        case TangentialLaw::directional_coulomb:
            law.tangential = DirectionalCoulomb{};
            break;
        case TangentialLaw::coulomb_spring:
            law.tangential = CoulombSpring{};
            break;
    }
    if (o.rolling == RollingLaw::none) {
        law.rolling = NoRolling{};
    } else {
        law.rolling = ConstantRollingTorque{};
    }
    return law;
}

double linear_restitution_from_zeta(double zeta) {
    // No tensile force: the pair separates when k x + c x' = 0, at omega t* = pi - phi with
    // tan phi = 2 zeta sqrt(1 - zeta^2) / (1 - 2 zeta^2), and e = exp(-beta t*)
    // (Schwager & Poeschel, Phys. Rev. E 75, 051304, 2007, eq. 22).
    if (zeta <= 0.0) return 1.0;
    if (zeta >= 1.0) return 0.0;
    const double s = std::sqrt(1.0 - zeta * zeta);
    const double phi = std::atan2(2.0 * zeta * s, 1.0 - 2.0 * zeta * zeta);
    return std::exp(-zeta / s * (kPi - phi));
}

double linear_zeta_from_restitution(double e) {
    if (e >= 1.0) return 0.0;
    // Start from the closed form without the clamp, -ln e / sqrt(pi^2 + ln^2 e), then solve
    // the exact clamped relation by bisection (it is monotonic in zeta).
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (linear_restitution_from_zeta(mid) > e) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

double hertz_restitution_from_alpha(double alpha) {
    // Dimensionless impact: m = k = v0 = 1, x'' = -max(0, x^1.5 + alpha x^0.25 x'), RK4 with
    // a step far below the contact time (about 3.2); ends when the force vanishes (no tension).
    double x = 0.0, v = 1.0;
    const double h = 2e-4;
    auto acc = [alpha](double xx, double vv) {
        if (xx <= 0.0) return 0.0;
        const double f = xx * std::sqrt(xx) + alpha * std::sqrt(std::sqrt(xx)) * vv;
        return -std::max(0.0, f);
    };
    for (int it = 0; it < 1000000; ++it) {
        const double k1x = v, k1v = acc(x, v);
        const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
        const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
        const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
        x += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
        v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
        if (v < 0.0 && (x <= 0.0 || acc(x, v) == 0.0)) break;
    }
    return -v;
}

double effective_modulus_pa(const Material& a, const Material& b) {
    return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_pa +
                  (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_pa);
}

double hertz_equivalent_radius(double r_x, double r_y) {
    const double r_large = std::max(r_x, r_y), r_small = std::min(r_x, r_y);
    const double ratio = r_large / r_small;  // = B / A >= 1
    // Below this the contact is circular to double precision in R_e (R_e/sqrt(r_x r_y) - 1 is
    // of order (ratio - 1)^2), and K - E would cancel.
    if (ratio < 1.0 + 1e-6) return std::sqrt(r_x * r_y);
    // B/A grows monotonically as b/a falls: bisect q = b/a on a log scale.
    auto b_over_a = [](double q) {
        const double m = 1.0 - q * q;  // e^2
        const double e = std::sqrt(m);
        const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
        return (ee / (q * q) - kk) / (kk - ee);
    };
    double lo = std::log(1e-12), hi = 0.0;  // ln q
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (b_over_a(std::exp(mid)) > ratio) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const double q = std::exp(0.5 * (lo + hi));
    const double e = std::sqrt(1.0 - q * q);
    const double kk = std::comp_ellint_1(e), ee = std::comp_ellint_2(e);
    const double a_plus_b = 0.5 / r_large + 0.5 / r_small;
    return kPi * kPi * ee / (4.0 * a_plus_b * q * q * kk * kk * kk);
}

double hertz_alpha_from_restitution(double e) {
    if (e >= 1.0) return 0.0;
    // Fifty integrations of an impact: remembered per restitution, since every solver of a
    // campaign (and the automatic time step's many single impacts) asks for the same few.
    static std::mutex mutex;
    static std::map<double, double> solved;
    {
        const std::lock_guard<std::mutex> lock(mutex);
        if (const auto it = solved.find(e); it != solved.end()) return it->second;
    }
    double lo = 0.0, hi = 10.0;  // e(alpha) decreases monotonically
    for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (hertz_restitution_from_alpha(mid) > e) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const double alpha = 0.5 * (lo + hi);
    const std::lock_guard<std::mutex> lock(mutex);
    solved.emplace(e, alpha);
    return alpha;
}

}  // namespace sb::dem

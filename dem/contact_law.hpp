// Contact law pieces in fixed slots (normal, damping, tangential, rolling), composed at
// compile time: one std::variant per slot, visited once per force evaluation (style.md).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "dem/options.hpp"

namespace sb::dem {

/// Kinematics of one contact, as seen from particle i (j is a particle or a wall).
struct ContactKinematics {
    double delta = 0.0;                  ///< overlap [m], > 0 in contact
    double delta_dot = 0.0;              ///< overlap rate [m/s], > 0 approaching
    Eigen::Vector3d n{0, 0, 1};          ///< unit normal from j towards i
    Eigen::Vector3d v_t{0, 0, 0};        ///< slip velocity of i relative to j at the contact [m/s]
    Eigen::Vector3d omega_rel{0, 0, 0};  ///< omega_i - omega_j [rad/s]
    double m_eff = 0.0;                  ///< effective mass [kg]
    double r_eff = 0.0;                  ///< effective radius R* (rolling lever arm) [m]
    /// Effective radius of curvature of the Hertz contact [m]: R* for two spheres, from the
    /// wall's curvature for walls (hertz_equivalent_radius).
    double r_hertz = 0.0;
    double m_t = 0.0;    ///< effective tangential mass at the contact point [kg]
    double i_eff = 0.0;  ///< effective rolling inertia [kg m^2]
    double dt = 0.0;     ///< time step [s]
};

/// Coefficients of one pair type, derived once at set-up.
struct PairCoefficients {
    double k_n = 0.0;                 ///< Hooke [N/m] or Hertz [N/m^1.5] (if > 0; else from e_star)
    double e_star_sqrt_factor = 0.0;  ///< Hertz from materials: k = 4/3 E* sqrt(R*) [Pa]
    /// zeta (linear), alpha (Hertz), dimensionless; A (viscoelastic) [s]; c (viscous) [N s/m]
    double damping = 0.0;
    double mu = 0.0;              ///< sliding friction [-]
    double mu_r = 0.0;            ///< rolling friction [-]
    double kt_ratio = 2.0 / 7.0;  ///< tangential / normal stiffness [-]
    double slip_reg = 1e-4;       ///< regularisation speed [m/s]
};

/// What the normal piece returns.
struct NormalResult {
    double f_spring = 0.0;  ///< elastic force [N], >= 0
    double k_linear = 0.0;  ///< tangent-like stiffness for damping and the tangential spring
                            ///< [N/m]: k (Hooke), k sqrt(delta) (Hertz)
    double k_law = 0.0;     ///< the law's constant [N/m or N/m^1.5]
};

// ---------------------------------------------------------------- normal slot

/// Linear spring: F = k delta.
struct Hooke {
    static constexpr const char* kName = "hooke";
    NormalResult evaluate(const ContactKinematics& c, const PairCoefficients& p) const {
        return {p.k_n * c.delta, p.k_n, p.k_n};
    }
    /// Stored elastic energy k delta^2 / 2 [J].
    static double energy(double k, double delta) { return 0.5 * k * delta * delta; }
};

/// Hertz: F = k delta^{3/2}, k = 4/3 E* sqrt(R*) (paper 004 eqs. 3-4; Johnson 1985), R* the
/// effective radius of curvature of the contact (c.r_hertz).
struct Hertz {
    static constexpr const char* kName = "hertz";
    NormalResult evaluate(const ContactKinematics& c, const PairCoefficients& p) const {
        const double k = p.k_n > 0.0 ? p.k_n : p.e_star_sqrt_factor * std::sqrt(c.r_hertz);
        const double sd = std::sqrt(c.delta);
        return {k * c.delta * sd, k * sd, k};
    }
    /// Stored elastic energy 2/5 k delta^{5/2} [J].
    static double energy(double k, double delta) {
        return 0.4 * k * delta * delta * std::sqrt(delta);
    }
};

// --------------------------------------------------------------- damping slot

struct NoDamping {
    static constexpr const char* kName = "none";
    double evaluate(const ContactKinematics&, const PairCoefficients&, const NormalResult&) const {
        return 0.0;
    }
};

/// Linear dashpot F_d = 2 zeta sqrt(k m*) delta_dot, zeta from the restitution by the exact
/// closed form of the spring-dashpot without tensile force (Schwager & Poeschel, PRE 2007).
struct LinearDashpot {
    static constexpr const char* kName = "linear_dashpot";
    double evaluate(const ContactKinematics& c, const PairCoefficients& p,
                    const NormalResult& nr) const {
        return 2.0 * p.damping * std::sqrt(nr.k_law * c.m_eff) * c.delta_dot;
    }
};

/// Hertz dashpot F_d = alpha sqrt(m* k) delta^{1/4} delta_dot (Tsuji, Tanaka & Ishida,
/// Powder Technol. 71, 1992; paper 004 eq. 3): the restitution depends on alpha only; alpha(e)
/// is solved once at set-up (hertz_alpha_from_restitution), cf. Antypov & Elliott, EPL 2011.
struct HertzDashpot {
    static constexpr const char* kName = "hertz_dashpot";
    double evaluate(const ContactKinematics& c, const PairCoefficients& p,
                    const NormalResult& nr) const {
        return p.damping * std::sqrt(c.m_eff * nr.k_law) * std::sqrt(std::sqrt(c.delta)) *
               c.delta_dot;
    }
};

/// Viscoelastic dashpot F_d = 3/2 A k sqrt(delta) delta_dot (Brilliantov, Spahn, Hertzsch &
/// Poeschel, PRE 53, 1996; Kuwabara & Kono 1987), A the material's dissipative constant [s]:
/// unlike the dashpots above, whose restitution is set, its restitution falls with the impact
/// speed, 1 - e = 1.15344 beta v^(1/5) + O(beta^2 v^(2/5)) with beta = 3/2 A (k/m*)^(2/5)
/// (Ramirez, Poeschel, Brilliantov & Schwager, PRE 60, 1999). p.damping holds A.
struct Viscoelastic {
    static constexpr const char* kName = "viscoelastic";
    double evaluate(const ContactKinematics& c, const PairCoefficients& p,
                    const NormalResult& nr) const {
        return 1.5 * p.damping * nr.k_linear * c.delta_dot;
    }
};

/// A dashpot of given coefficient, F_d = c delta_dot [N s/m], as a drop-bounce test measures
/// it (paper 003, Table 4: c = 0.7 N s/m beside k = 40.76 kN/m for a rubber sphere): with
/// Hooke its restitution is that of the spring-dashpot with zeta = c / (2 sqrt(k m*)), so it
/// depends on the pair's mass, where a set restitution does not.
struct ViscousDashpot {
    static constexpr const char* kName = "viscous";
    double evaluate(const ContactKinematics& c, const PairCoefficients& p,
                    const NormalResult&) const {
        return p.damping * c.delta_dot;
    }
};

// ------------------------------------------------------------ tangential slot

struct NoFriction {
    static constexpr const char* kName = "none";
    static constexpr bool kHasHistory = false;
    Eigen::Vector3d evaluate(const ContactKinematics&, const PairCoefficients&, double,
                             const NormalResult&, Eigen::Vector3d&) const {
        return Eigen::Vector3d::Zero();
    }
};

/// Stateless directional Coulomb friction F_t = -mu F_n t_hat, t_hat = v_t/|v_t| (papers
/// 000, 001 eq. 2), ramped linearly below slip_reg and capped so that the slip of the pair
/// is not reversed within one step (|F_t| <= m_t |v_t| / (2 dt)).
struct DirectionalCoulomb {
    static constexpr const char* kName = "directional_coulomb";
    static constexpr bool kHasHistory = false;
    Eigen::Vector3d evaluate(const ContactKinematics& c, const PairCoefficients& p, double f_n,
                             const NormalResult&, Eigen::Vector3d&) const {
        const double s = c.v_t.norm();
        if (s <= 0.0) return Eigen::Vector3d::Zero();
        double f = p.mu * f_n * std::min(1.0, s / p.slip_reg);
        f = std::min(f, 0.5 * c.m_t * s / c.dt);
        return (-f / s) * c.v_t;
    }
};

/// History spring capped by Coulomb (static friction; Cundall & Strack 1979, LAMMPS
/// linear_history): xi is projected onto the current tangent plane keeping its length
/// (rotation with the pair), then xi += v_t dt, F_t = -k_t xi, |F_t| <= mu F_n with xi reset
/// to -F_t/k_t on slip.
struct CoulombSpring {
    static constexpr const char* kName = "coulomb_spring";
    static constexpr bool kHasHistory = true;
    Eigen::Vector3d evaluate(const ContactKinematics& c, const PairCoefficients& p, double f_n,
                             const NormalResult& nr, Eigen::Vector3d& xi) const {
        const double len = xi.norm();
        if (len > 0.0) {
            xi -= c.n * c.n.dot(xi);
            const double len2 = xi.norm();
            xi *= len2 > 0.0 ? len / len2 : 0.0;
        }
        xi += c.v_t * c.dt;
        const double kt = p.kt_ratio * nr.k_linear;
        Eigen::Vector3d f = -kt * xi;
        const double fmax = p.mu * f_n;
        const double fm = f.norm();
        if (fm > fmax) {
            f *= fmax / fm;
            xi = kt > 0.0 ? Eigen::Vector3d(-f / kt) : Eigen::Vector3d::Zero();
        }
        return f;
    }
};

// --------------------------------------------------------------- rolling slot

struct NoRolling {
    static constexpr const char* kName = "none";
    Eigen::Vector3d evaluate(const ContactKinematics&, const PairCoefficients&, double) const {
        return Eigen::Vector3d::Zero();
    }
};

/// Constant rolling torque M = -mu_r R* F_n w_hat opposing the relative rolling angular
/// velocity w (tangential part of omega_i - omega_j) (paper 000 rolling friction; Zhou et
/// al., Physica A 1999, model A), capped so that w is not reversed within one step.
struct ConstantRollingTorque {
    static constexpr const char* kName = "constant_torque";
    Eigen::Vector3d evaluate(const ContactKinematics& c, const PairCoefficients& p,
                             double f_n) const {
        const Eigen::Vector3d w = c.omega_rel - c.n * c.n.dot(c.omega_rel);
        const double s = w.norm();
        if (s <= 0.0) return Eigen::Vector3d::Zero();
        double m = p.mu_r * c.r_eff * f_n;
        m = std::min(m, 0.5 * c.i_eff * s / c.dt);
        return (-m / s) * w;
    }
};

using NormalPiece = std::variant<Hooke, Hertz>;
using DampingPiece =
    std::variant<NoDamping, LinearDashpot, HertzDashpot, Viscoelastic, ViscousDashpot>;
using TangentialPiece = std::variant<NoFriction, DirectionalCoulomb, CoulombSpring>;
using RollingPiece = std::variant<NoRolling, ConstantRollingTorque>;

/// What a composed law returns for one contact.
struct LawForce {
    double fn = 0.0;              ///< normal force, spring + damping clamped at 0 (no tension) [N]
    double f_spring = 0.0;        ///< elastic part [N]
    double k_law = 0.0;           ///< the normal law's constant
    Eigen::Vector3d ft{0, 0, 0};  ///< tangential force on i [N]
    Eigen::Vector3d mr{0, 0, 0};  ///< rolling torque on i [N m]
};

/// The four pieces of one step's law as concrete types (the variants visited once per step):
/// everything below inlines into the contact loop.
template <class N, class D, class T, class R>
struct ComposedLaw {
    static constexpr bool kHasHistory = T::kHasHistory;
    N normal;
    D damping;
    T tangential;
    R rolling;
    LawForce evaluate(const ContactKinematics& k, const PairCoefficients& p,
                      Eigen::Vector3d& history) const {
        const NormalResult nr = normal.evaluate(k, p);
        const double fd = damping.evaluate(k, p, nr);
        const double fn = std::max(0.0, nr.f_spring + fd);  // no tensile force
        return {fn, nr.f_spring, nr.k_law, tangential.evaluate(k, p, fn, nr, history),
                rolling.evaluate(k, p, fn)};
    }
};

// ------------------------------------------------------------ the registry

/// The names of each slot's choices, one row per piece (the config reads and writes these).
/// `restitution` is not a piece: it picks the dashpot that matches the normal law.
inline constexpr std::pair<NormalLaw, std::string_view> kNormalLawNames[] = {
    {NormalLaw::hooke, Hooke::kName}, {NormalLaw::hertz, Hertz::kName}};
inline constexpr std::pair<DampingLaw, std::string_view> kDampingLawNames[] = {
    {DampingLaw::restitution, "restitution"},
    {DampingLaw::none, NoDamping::kName},
    {DampingLaw::linear_dashpot, LinearDashpot::kName},
    {DampingLaw::hertz_dashpot, HertzDashpot::kName},
    {DampingLaw::viscoelastic, Viscoelastic::kName},
    {DampingLaw::viscous, ViscousDashpot::kName}};
inline constexpr std::pair<TangentialLaw, std::string_view> kTangentialLawNames[] = {
    {TangentialLaw::directional_coulomb, DirectionalCoulomb::kName},
    {TangentialLaw::coulomb_spring, CoulombSpring::kName},
    {TangentialLaw::none, NoFriction::kName}};
inline constexpr std::pair<RollingLaw, std::string_view> kRollingLawNames[] = {
    {RollingLaw::constant_torque, ConstantRollingTorque::kName},
    {RollingLaw::none, NoRolling::kName}};

/// A composed contact law.
struct ContactLaw {
    NormalPiece normal{};
    DampingPiece damping{};
    TangentialPiece tangential{};
    RollingPiece rolling{};
    std::string describe() const;
};

/// Builds the law from options (ContactOptions::validate() reports incompatible pieces,
/// naming both).
ContactLaw make_contact_law(const ContactOptions& options);

/// Effective radius R_e of a Hertz contact whose relative principal radii of curvature are
/// r_x and r_y [m] (1/r = sum of both surfaces' curvatures in that direction, concave < 0),
/// such that F = 4/3 E* sqrt(R_e) delta^{3/2} holds exactly. The contact is elliptical
/// (semi-axes a >= b, eccentricity e): with A = 1/(2 r_large), B = 1/(2 r_small),
/// B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)), p0 = (A + B) E* b / E(e),
/// delta = p0 b K(e) / E*, F = 2/3 pi a b p0 (Johnson, Contact Mechanics, 1985, eqs. 3.42
/// and 3.46), hence R_e = pi^2 (a/b)^2 E(e) / (4 (A + B) K(e)^3). For r_x = r_y it is r_x
/// (sphere); for r_large / r_small = 2 and 4 it is 1.02 and 1.08 times sqrt(r_x r_y).
/// Examples: a sphere R on a rod R_rod: r_x = R (along the rod), r_y = 1/(1/R + 1/R_rod);
/// inside a cylinder wall R_c: r_x = R (along the axis), r_y = 1/(1/R - 1/R_c).
/// Solved by bisection at set-up (never per contact).
double hertz_equivalent_radius(double r_x, double r_y);

/// Hertz effective modulus E* = 1 / ((1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b) of two materials [Pa]
/// (Johnson, Contact Mechanics, 1985, §4.2).
double effective_modulus_pa(const Material& a, const Material& b);

/// Restitution of the linear spring-dashpot with damping ratio zeta and no tensile force.
double linear_restitution_from_zeta(double zeta);
/// zeta of the linear dashpot giving restitution e with no tensile force (inverts the closed
/// form of linear_restitution_from_zeta; without the clamp it would be -ln e/sqrt(pi^2+ln^2 e)).
double linear_zeta_from_restitution(double e);
/// alpha of the Hertz dashpot giving restitution e (solved numerically, no tensile force).
double hertz_alpha_from_restitution(double e);
/// Restitution of the Hertz dashpot law with alpha, integrated numerically (for tests).
double hertz_restitution_from_alpha(double alpha);

}  // namespace sb::dem

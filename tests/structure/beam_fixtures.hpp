// Beam specs of the seed papers and helpers shared by the structure test suites.
#pragma once

#include <cmath>
#include <vector>

#include "core/units.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/spec.hpp"

namespace sb::structure::testing {

inline Support support(const std::string& name, double x_m, SupportKind kind) {
    Support s;
    s.name = name;
    s.x_m = x_m;
    s.kind = kind;
    return s;
}

/// 1 m x 40 mm x 5 mm steel strip, Euler-Bernoulli, 40 elements (E I = 87.5 N m^2 in z), with
/// no supports and no points: the analytic cases add their own.
inline BeamSpec steel_strip() {
    BeamSpec b;
    b.length_m = 1.0;
    b.width_m = 0.04;
    b.thickness_m = 0.005;
    b.density_kg_m3 = 7850.0;
    b.youngs_modulus_pa = 210e9;
    b.min_elements = 40;
    return b;
}

/// Paper 000 (Table 1) aluminium beam clamped at x = 0, without any attachment.
inline BeamSpec paper000_bare_beam() {
    BeamSpec b;
    b.length_m = 0.543;
    b.width_m = 0.05;
    b.thickness_m = 0.003;
    b.density_kg_m3 = 2695.0;
    b.youngs_modulus_pa = 72e9;
    b.shear_modulus_pa = 27e9;
    b.min_elements = 40;
    b.supports = {support("root", 0.0, SupportKind::clamped)};
    return b;
}

inline LumpedMass lumped(const std::string& name, double x_m, double mass_kg) {
    LumpedMass m;
    m.name = name;
    m.x_m = x_m;
    m.mass_kg = mass_kg;
    return m;
}

/// Paper 000 beam with its load cell (shaker point), four accelerometers and the damper
/// (empty enclosure 23.8 g + 120 particles 13.2 g as one rigid mass) at 0.533 m. The enclosure
/// sits on the beam's face: a 10 mm base plate and the 25 mm high cavity (19 mm bore), so its
/// CG is about 1.5 mm (half the beam) + 14 mm above the axis along z; its inertia is that of a
/// solid cylinder of 12.5 mm radius and 37 mm height of the same mass (a plausible estimate).
inline StructureSpec paper000_loaded() {
    StructureSpec spec;
    spec.kind = StructureSpec::Kind::beam;
    spec.beam = paper000_bare_beam();
    spec.beam.masses = {lumped("load_cell", 0.160, 0.030), lumped("acc1", 0.075, 0.005),
                        lumped("acc2", 0.241, 0.005), lumped("acc3", 0.382, 0.005),
                        lumped("acc4", 0.519, 0.005)};
    LumpedMass damper = lumped("damper", 0.533, 0.0238 + 0.0132);
    const double radius = 0.0125;
    const double height = 0.037;
    const double m = damper.mass_kg;
    const double transverse = m * (3.0 * radius * radius + height * height) / 12.0;
    damper.inertia_kg_m2 = {transverse, transverse, 0.5 * m * radius * radius};
    damper.offset_m = {0.0, 0.0, 0.0015 + 0.014};
    spec.beam.masses.push_back(damper);
    spec.beam.points = {NamedPoint{"shaker", 0.160}};
    spec.excitation.kind = ExcitationSpec::Kind::force;
    spec.excitation.point = "shaker";
    spec.excitation.direction = Eigen::Vector3d::UnitZ();
    spec.damping.default_ratio = 0.005;
    spec.modes = 6;
    return spec;
}

/// Share of a mode's sampled translation that lies along axis `axis` [-].
inline double translation_share(const LinearModel& model, const ModalBasis& basis, int mode,
                                int axis) {
    const Eigen::VectorXd u = model.sample_translation() * basis.shapes.col(mode);
    double along = 0.0;
    double total = 0.0;
    for (Eigen::Index j = 0; j < u.size(); ++j) {
        total += u(j) * u(j);
        if (j % 3 == axis) along += u(j) * u(j);
    }
    return total > 0.0 ? along / total : 0.0;
}

/// Frequencies [Hz] of the modes whose translation is mostly along `axis`, ascending.
inline std::vector<double> bending_frequencies(const LinearModel& model, const ModalBasis& basis,
                                               int axis) {
    constexpr double kDominantShare = 0.9;  // bending modes are > 0.99 along their axis
    std::vector<double> out;
    for (int r = 0; r < static_cast<int>(basis.modes.size()); ++r) {
        if (translation_share(model, basis, r, axis) > kDominantShare) {
            out.push_back(basis.modes[static_cast<std::size_t>(r)].frequency_hz);
        }
    }
    return out;
}

/// Euler-Bernoulli bending frequency [Hz] for a root beta L (Blevins, Formulas for Natural
/// Frequency and Mode Shape, Table 8-1): f = (beta L)^2 / (2 pi L^2) sqrt(E I / (rho A)).
inline double euler_bernoulli_hz(double beta_l, const BeamSpec& b) {
    const double i = b.width_m * std::pow(b.thickness_m, 3) / 12.0;
    const double a = b.width_m * b.thickness_m;
    return beta_l * beta_l / (kTwoPi * b.length_m * b.length_m) *
           std::sqrt(b.youngs_modulus_pa * i / (b.density_kg_m3 * a));
}

}  // namespace sb::structure::testing

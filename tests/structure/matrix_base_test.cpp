// Base excitation of an imported model and masses added at its named points, against the
// closed-form transmissibility of a two-mass chain on a moving base.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/units.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/reduced_modal_model.hpp"

namespace sb::structure {
namespace {

using namespace std::complex_literals;

// The chain: base -k1- m1 -k2- m2, along z. Rayleigh damping C = alpha M + beta K in
// coordinates relative to the base.
constexpr double kM1 = 1.0;     // [kg]
constexpr double kM2 = 0.5;     // [kg]
constexpr double kK1 = 4.0e4;   // [N/m]
constexpr double kK2 = 1.0e4;   // [N/m]
constexpr double kAlpha = 0.8;  // [1/s]
constexpr double kBeta = 2e-5;  // [s]
// Modes near 19.1 Hz and 37.5 Hz: below, at, between, at and above them.
const std::vector<double> kFrequenciesHz = {5.0, 19.09, 28.0, 37.53, 80.0};
// The modal solution with both modes kept is exact for Rayleigh damping; only round-off
// separates it from the closed form.
constexpr double kSteadyTolerance = 1e-9;

/// Closed-form complex transmissibilities X1/X_b and X2/X_b in absolute coordinates, written
/// from the physical chain: springs k1 (base-m1) and k2 (m1-m2), dashpots beta k1 and
/// beta k2 across them, and alpha m_i from each mass to the moving base (mass-proportional
/// damping acts on the motion relative to the base). Under x_b = X_b e^{iWt}:
///   [k1 + k2 - W^2 m1 + iW(c1 + c2 + a1), -(k2 + iW c2)] [X1]   [k1 + iW (c1 + a1)]
///   [-(k2 + iW c2), k2 - W^2 m2 + iW(c2 + a2)          ] [X2] = [iW a2            ] X_b
/// with c_i = beta k_i, a_i = alpha m_i; solved by Cramer's rule.
std::pair<std::complex<double>, std::complex<double>> chain_transmissibility(double m1, double m2,
                                                                             double f_hz) {
    const double w = kTwoPi * f_hz;
    const double c1 = kBeta * kK1, c2 = kBeta * kK2, a1 = kAlpha * m1, a2 = kAlpha * m2;
    const std::complex<double> d11 = kK1 + kK2 - w * w * m1 + 1i * w * (c1 + c2 + a1);
    const std::complex<double> d12 = -(kK2 + 1i * w * c2);
    const std::complex<double> d22 = kK2 - w * w * m2 + 1i * w * (c2 + a2);
    const std::complex<double> b1 = kK1 + 1i * w * (c1 + a1);
    const std::complex<double> b2 = 1i * w * a2;
    const std::complex<double> det = d11 * d22 - d12 * d12;
    return {(b1 * d22 - d12 * b2) / det, (d11 * b2 - d12 * b1) / det};
}

std::filesystem::path dir() { return std::filesystem::temp_directory_path(); }

void write(const std::string& name, const std::string& text) {
    std::ofstream(dir() / ("sb_matrix_base_" + name)) << text;
}

/// The chain's files (free DOFs m1, m2; the base constrained out) and a spec driving its
/// base along z. m1 is named without suffix (a DOF along the excitation direction), m2 as
/// "m2.z": both ways of naming a translation.
StructureSpec chain_spec() {
    write("m.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 " +
                       std::to_string(kM1) + "\n2 2 " + std::to_string(kM2) + "\n");
    write("k.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 " +
                       std::to_string(kK1 + kK2) + "\n2 1 " + std::to_string(-kK2) + "\n2 2 " +
                       std::to_string(kK2) + "\n");
    StructureSpec spec;
    spec.kind = StructureSpec::Kind::matrix;
    spec.matrix.mass_file = "sb_matrix_base_m.mtx";
    spec.matrix.stiffness_file = "sb_matrix_base_k.mtx";
    spec.matrix.named_dofs = {{"m1", 0}, {"m2.z", 1}};
    spec.damping.model = DampingSpec::Model::rayleigh;
    spec.damping.alpha_per_s = kAlpha;
    spec.damping.beta_s = kBeta;
    spec.excitation.kind = ExcitationSpec::Kind::base;
    spec.excitation.direction = Eigen::Vector3d::UnitZ();
    spec.modes = 2;
    return spec;
}

/// The model's complex amplitude of a point's absolute z acceleration per unit base
/// acceleration, from its linear steady state under a_b = A sin(Wt) = Re(-iA e^{iWt}): the
/// response Re(X e^{iWt}) reads X = a(0) - i a(T/4). The same ratio holds for displacements.
struct Response {
    std::complex<double> acceleration;
    std::complex<double> displacement;
};
Response model_transmissibility(const LinearModel& model, const ModalBasis& basis,
                                const std::string& point, double f_hz) {
    constexpr double kAmplitude = 3.0;  // [m/s^2]
    const double w = kTwoPi * f_hz;
    ReducedModalModel sim(model, basis, 1e-4);
    const auto at = [&](double t) {
        sim.set_harmonic_base_steady_state(kAmplitude, f_hz, t);
        return std::pair{sim.acceleration(point).z(), sim.displacement(point).z()};
    };
    const auto [a0, u0] = at(0.0);
    const auto [a1, u1] = at(0.25 / f_hz);
    const std::complex<double> base_acceleration = -1i * kAmplitude;
    const std::complex<double> base_displacement = base_acceleration / (-w * w);
    return {(a0 - 1i * a1) / base_acceleration, (u0 - 1i * u1) / base_displacement};
}

void expect_chain(const StructureSpec& spec, double m1, double m2) {
    const LinearModel model = build_linear_model(spec, dir());
    const ModalBasis basis = compute_modes(model, spec.damping, 2);
    // The rigid translation along z carries every mass: the effective masses sum to it.
    EXPECT_NEAR(basis.modes[0].effective_mass_kg.z() + basis.modes[1].effective_mass_kg.z(),
                m1 + m2, 1e-12);
    for (double f : kFrequenciesHz) {
        const auto [t1, t2] = chain_transmissibility(m1, m2, f);
        const Response r1 = model_transmissibility(model, basis, "m1", f);
        const Response r2 = model_transmissibility(model, basis, "m2", f);
        EXPECT_LT(std::abs(r2.acceleration / t2 - 1.0), kSteadyTolerance)
            << f << " Hz: |X2/Xb| " << std::abs(r2.acceleration) << " against " << std::abs(t2)
            << ", error " << std::abs(r2.acceleration / t2 - 1.0);
        EXPECT_LT(std::abs(r1.acceleration / t1 - 1.0), kSteadyTolerance) << f << " Hz";
        EXPECT_LT(std::abs(r2.displacement / t2 - 1.0), kSteadyTolerance) << f << " Hz";
    }
}

TEST(MatrixModelBase, TwoMassChainHasTheClosedFormTransmissibility) {
    expect_chain(chain_spec(), kM1, kM2);
}

TEST(MatrixModelBase, SteppedFromItsSteadyStateTheChainKeepsTheClosedFormResponse) {
    // The modal steps are exact for loads linear within a step; the sine's interpolation
    // shifts the response by about (W dt)^2/12 = 8e-7 at 2000 steps per period (a few times
    // that where two modes' shares cancel, between them).
    constexpr int kSteps = 2000;
    constexpr double kAmplitude = 3.0;
    const StructureSpec spec = chain_spec();
    const LinearModel model = build_linear_model(spec, dir());
    const ModalBasis basis = compute_modes(model, spec.damping, 2);
    for (double f : {19.09, 28.0}) {
        const double w = kTwoPi * f;
        ReducedModalModel sim(model, basis, 1.0 / (f * kSteps));
        sim.set_harmonic_base_steady_state(kAmplitude, f, 0.0);
        const std::complex<double> expected = chain_transmissibility(kM1, kM2, f).second;
        double error = 0.0;
        for (int n = 0; n < 3 * kSteps; ++n) {
            const double t = sim.time_s() + sim.dt_s();
            sim.set_base_motion(-kAmplitude / (w * w) * std::sin(w * t),
                                -kAmplitude / w * std::cos(w * t), kAmplitude * std::sin(w * t));
            sim.step();
            const double closed =
                (expected * (-1i * kAmplitude) * std::exp(1i * (w * sim.time_s()))).real();
            error = std::max(error, std::abs(sim.acceleration("m2").z() - closed));
        }
        EXPECT_LT(error / (std::abs(expected) * kAmplitude), 1e-5)
            << f << " Hz: error " << error / (std::abs(expected) * kAmplitude);
    }
}

TEST(MatrixModelBase, MassesAddedAtNamedPointsMakeTheChainHeavier) {
    StructureSpec spec = chain_spec();
    // One on the suffix-less DOF, one on "m2.z": each adds to its point's translation.
    spec.matrix.masses.push_back({"block", "m1", 0.25, {}, {}});
    spec.matrix.masses.push_back({"", "m2", 0.1, {}, {}});
    expect_chain(spec, kM1 + 0.25, kM2 + 0.1);
}

TEST(MatrixModelBase, AnInfluenceFileDrivesAPartlyNamedImport) {
    // Only m2 named: the rigid translation is unknown, the file gives r = [1, 1].
    StructureSpec spec = chain_spec();
    spec.matrix.named_dofs = {{"m2.z", 1}};
    write("r.mtx", "%%MatrixMarket matrix coordinate real general\n2 1 2\n1 1 1.0\n2 1 1.0\n");
    spec.matrix.base_influence_file = "sb_matrix_base_r.mtx";
    const LinearModel model = build_linear_model(spec, dir());
    const ModalBasis basis = compute_modes(model, spec.damping, 2);
    for (double f : kFrequenciesHz) {
        const auto t2 = chain_transmissibility(kM1, kM2, f).second;
        EXPECT_LT(std::abs(model_transmissibility(model, basis, "m2", f).acceleration / t2 - 1.0),
                  kSteadyTolerance)
            << f << " Hz";
    }
}

/// The message of the std::invalid_argument building the model throws, or a failure.
std::string build_error(const StructureSpec& spec) {
    try {
        (void)build_linear_model(spec, dir());
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    ADD_FAILURE() << "no std::invalid_argument";
    return {};
}

TEST(MatrixModelBase, AnInfluenceFileOfTheWrongSizeIsAnErrorNamingIt) {
    StructureSpec spec = chain_spec();
    write("r3.mtx", "%%MatrixMarket matrix coordinate real general\n3 1 1\n1 1 1.0\n");
    spec.matrix.base_influence_file = "sb_matrix_base_r3.mtx";
    const std::string message = build_error(spec);
    EXPECT_NE(message.find("sb_matrix_base_r3.mtx: 3x1, expected 2x1"), std::string::npos)
        << message;
    EXPECT_NE(message.find("structure.matrix.base_influence_file"), std::string::npos) << message;
}

TEST(MatrixModelBase, WithoutRigidTranslationOrInfluenceFileTheKeyIsNamed) {
    StructureSpec spec = chain_spec();
    spec.matrix.named_dofs = {{"m2.z", 1}};
    const std::string message = build_error(spec);
    EXPECT_EQ(message.rfind("structure.matrix.base_influence_file is required", 0), 0u) << message;
    // Under force excitation nothing needs the influence vector.
    spec.excitation.kind = ExcitationSpec::Kind::force;
    spec.excitation.point = "m2";
    EXPECT_NO_THROW((void)build_linear_model(spec, dir()));
}

TEST(MatrixModelBase, ASupportIsRefusedAndAnInfluenceFileNeedsBaseExcitation) {
    StructureSpec spec = chain_spec();
    EXPECT_TRUE(spec.validate().empty());
    spec.excitation.support = "root";
    const Violations with_support = spec.validate();
    ASSERT_EQ(with_support.size(), 1u);
    EXPECT_EQ(with_support[0].key, "excitation.support");
    spec.excitation.support.clear();
    spec.excitation.kind = ExcitationSpec::Kind::force;
    spec.excitation.point = "m2";
    spec.matrix.base_influence_file = "r.mtx";
    const Violations with_file = spec.validate();
    ASSERT_EQ(with_file.size(), 1u);
    EXPECT_EQ(with_file[0].key, "matrix.base_influence_file");
}

TEST(MatrixModelBase, ABeamOrLumpedModelStillNeedsItsSupport) {
    StructureSpec spec;
    spec.kind = StructureSpec::Kind::lumped;
    spec.lumped.masses = {{"m", 1.0}};
    spec.lumped.springs = {{"ground", "m", 1e4, 0.0}};
    spec.excitation.kind = ExcitationSpec::Kind::base;
    const Violations v = spec.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "excitation.support");
    EXPECT_EQ(v[0].constraint, "must be \"ground\"");
    spec.excitation.support = "ground";
    EXPECT_TRUE(spec.validate().empty());
}

TEST(MatrixModelBase, AMassAtAPointThatIsNotNamedIsAViolation) {
    StructureSpec spec = chain_spec();
    spec.matrix.masses.push_back({"", "nowhere", 0.1, {}, {}});
    const Violations v = spec.validate();
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].key, "matrix.masses[0].point");
}

}  // namespace
}  // namespace sb::structure

// The finite-element model of paper 001's instrument bracket (Hu et al.): a small frame of
// 3D beam elements carrying the instrument's equivalent load as a rigid body, its section sizes
// updated to the measured first mode (239.0 Hz, Y) and to the Z resonance regions of the
// paper's Fig. 3 (220-240, 1155-1185, 1550-1600 Hz). Writes the mass, stiffness and
// rigid-translation matrices that configs/paper001-bracket.toml imports, or checks that the
// committed files are what it builds (a test runs the check). docs/validation.md, paper 001,
// says what the model is and why.
//
//   shakerbench-paper001-bracket --write configs/paper001
//   shakerbench-paper001-bracket --check configs/paper001
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "structure/beam_element.hpp"
#include "structure/matrix_market.hpp"
#include "structure/rigid_mass.hpp"
#include "structure/section.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using sb::structure::BeamElementProperties;
using sb::structure::ElementMatrix;

/// Aluminium alloy of the bracket and the enclosures (paper 001, sec. 4.1) and steel of the
/// adapter that carries the instrument.
struct Material {
    double density_kg_m3;
    double youngs_modulus_pa;
    double poisson_ratio;
};
constexpr Material kAluminium{2700.0, 70.0e9, 0.33};
constexpr Material kSteel{7850.0, 200.0e9, 0.29};

/// Mass of the primary system (bracket and the instrument's equivalent load): paper 001,
/// sec. 4.1, 231.6 g of dampers are 3.1 % of it.
constexpr double kPrimaryMassKg = 0.2316 / 0.031;

/// The section sizes the model update moves, one per measured frequency it matches.
struct Sizes {
    double leg_thickness_m = 0.01;  ///< the legs' thickness along Y (their sway along Y)
    double leg_width_m = 0.04;      ///< the legs' width along X (their axial stiffness)
    double adapter_side_m = 0.015;  ///< the adapter's square spokes (the load's rocking)
};

/// Frame geometry [m]: four legs from the table to the corners of a rectangular deck, at
/// x = +-kHalfSpan and y = 0 (back) and kDepth (front), kHeight above the table; the deck's
/// members kDeckWidth wide and kDeckThickness thick.
constexpr double kHalfSpan = 0.06;
constexpr double kDepth = 0.10;
constexpr double kHeight = 0.08;
constexpr double kDeckWidth = 0.03;
constexpr double kDeckThickness = 0.015;
/// The legs lean forward (+Y) by this angle from the vertical (their feet 29 mm behind their
/// tops): a sway along Y then moves the deck along Z as well, as the paper's first mode
/// (239.0 Hz, Y) is one of the Z response's resonances too (paper 001, Fig. 3).
inline const double kLegLeanRad = 20.0 * std::numbers::pi / 180.0;
constexpr int kLegElements = 4;
constexpr int kDeckElements = 2;  ///< per deck member (a node at each member's middle)

/// The instrument's equivalent load (paper 001, sec. 2: same mass and moment of inertia as the
/// high-speed component): a 120 x 100 x 80 mm block whose centre of gravity is 40 mm above
/// the deck's centre; its mass makes up the primary system's total.
constexpr double kLoadSideX = 0.12, kLoadSideY = 0.10, kLoadHeight = 0.08;
constexpr double kLoadY = 0.07;  ///< the adapter node, forward of the deck's centre

struct Node {
    Vector3d position;
};

struct Member {
    int first, second;
    BeamElementProperties properties;
    Vector3d thickness_direction;  ///< global direction of the section's thickness t
};

struct Frame {
    std::vector<Node> nodes;  ///< node 0.. ; nodes with fixed = true are clamped
    std::vector<bool> fixed;
    std::vector<Member> members;
    std::map<std::string, int> named_nodes;
    int load_node = -1;

    int add_node(const Vector3d& p, bool is_fixed = false) {
        nodes.push_back({p});
        fixed.push_back(is_fixed);
        return static_cast<int>(nodes.size()) - 1;
    }
};

BeamElementProperties properties(const Material& m, double width_m, double thickness_m) {
    BeamElementProperties p;
    p.section = sb::structure::rectangular_section(width_m, thickness_m);
    p.density_kg_m3 = m.density_kg_m3;
    p.youngs_modulus_pa = m.youngs_modulus_pa;
    p.shear_modulus_pa = m.youngs_modulus_pa / (2.0 * (1.0 + m.poisson_ratio));
    p.timoshenko = true;  // the deck members are short against their depth
    return p;
}

/// A straight run of `elements` members from node a to a new node at b (intermediate nodes
/// made); returns the node at b, or `end` when given.
int add_run(Frame& f, int a, const Vector3d& b, int elements, const BeamElementProperties& p,
            const Vector3d& thickness_direction, int end = -1) {
    const Vector3d start = f.nodes[static_cast<std::size_t>(a)].position;
    int previous = a;
    for (int e = 1; e <= elements; ++e) {
        const int next =
            (e == elements && end >= 0)
                ? end
                : f.add_node(start + (b - start) * (static_cast<double>(e) / elements));
        f.members.push_back({previous, next, p, thickness_direction});
        previous = next;
    }
    return previous;
}

Frame build_frame(const Sizes& s) {
    Frame f;
    const auto leg = properties(kAluminium, s.leg_width_m, s.leg_thickness_m);
    const auto deck = properties(kAluminium, kDeckWidth, kDeckThickness);
    const auto adapter = properties(kSteel, s.adapter_side_m, s.adapter_side_m);
    const Vector3d ey = Vector3d::UnitY(), ez = Vector3d::UnitZ();

    // Four legs, clamped to the table (the low-speed component, far stiffer: paper 001 sec. 2),
    // the deck a rectangle on their tops.
    std::array<int, 4> top{};  // back left, back right, front left, front right
    for (int k = 0; k < 4; ++k) {
        const double x = k % 2 == 0 ? -kHalfSpan : kHalfSpan;
        const double y = k < 2 ? 0.0 : kDepth;
        const int foot = f.add_node({x, y - kHeight * std::tan(kLegLeanRad), 0.0}, true);
        top[static_cast<std::size_t>(k)] = add_run(f, foot, {x, y, kHeight}, kLegElements, leg, ey);
    }
    add_run(f, top[0], {kHalfSpan, 0.0, kHeight}, kDeckElements, deck, ez, top[1]);
    add_run(f, top[2], {kHalfSpan, kDepth, kHeight}, kDeckElements, deck, ez, top[3]);
    add_run(f, top[0], {-kHalfSpan, kDepth, kHeight}, kDeckElements, deck, ez, top[2]);
    add_run(f, top[1], {kHalfSpan, kDepth, kHeight}, kDeckElements, deck, ez, top[3]);

    auto node_at = [&](const Vector3d& p) {
        for (std::size_t i = 0; i < f.nodes.size(); ++i)
            if ((f.nodes[i].position - p).norm() < 1e-9) return static_cast<int>(i);
        throw std::logic_error("no node at the bracket point");
    };
    // The adapter: four spokes from the legs' tops to the instrument's node.
    f.load_node = f.add_node({0.0, kLoadY, kHeight});
    for (const int corner : top) f.members.push_back({corner, f.load_node, adapter, ez});

    // The sensor on the deck's front edge; dampers on the front corners and the sides' middles.
    f.named_nodes["sensor"] = node_at({0.0, kDepth, kHeight});
    f.named_nodes["d1"] = node_at({-kHalfSpan, kDepth, kHeight});
    f.named_nodes["d2"] = node_at({kHalfSpan, kDepth, kHeight});
    f.named_nodes["d3"] = node_at({-kHalfSpan, 0.5 * kDepth, kHeight});
    f.named_nodes["d4"] = node_at({kHalfSpan, 0.5 * kDepth, kHeight});
    f.named_nodes["load"] = f.load_node;
    return f;
}

/// Rotation from global to a member's local axes: local x along the member, local z along
/// its thickness (orthogonalised), local y = z x x, as the element's section expects.
Eigen::Matrix3d local_axes(const Vector3d& a, const Vector3d& b, const Vector3d& thickness) {
    const Vector3d x = (b - a).normalized();
    const Vector3d z = (thickness - thickness.dot(x) * x).normalized();
    const Vector3d y = z.cross(x);
    Eigen::Matrix3d r;
    r.row(0) = x.transpose();
    r.row(1) = y.transpose();
    r.row(2) = z.transpose();
    return r;
}

struct Matrices {
    MatrixXd mass, stiffness;
    std::vector<int> dof_of_node;  ///< first free DOF of each node, -1 if clamped
    double frame_mass_kg = 0.0;
};

Matrices assemble(const Frame& f) {
    Matrices out;
    int n = 0;
    for (bool is_fixed : f.fixed) {
        out.dof_of_node.push_back(is_fixed ? -1 : n);
        if (!is_fixed) n += 6;
    }
    out.mass = MatrixXd::Zero(n, n);
    out.stiffness = MatrixXd::Zero(n, n);
    for (const Member& m : f.members) {
        const Vector3d a = f.nodes[static_cast<std::size_t>(m.first)].position;
        const Vector3d b = f.nodes[static_cast<std::size_t>(m.second)].position;
        const double length = (b - a).norm();
        ElementMatrix t = ElementMatrix::Zero();
        const Eigen::Matrix3d r = local_axes(a, b, m.thickness_direction);
        for (int k = 0; k < 4; ++k) t.block<3, 3>(3 * k, 3 * k) = r;
        const ElementMatrix k_global =
            t.transpose() * sb::structure::beam_element_stiffness(m.properties, length) * t;
        const ElementMatrix m_global =
            t.transpose() * sb::structure::beam_element_mass(m.properties, length) * t;
        out.frame_mass_kg += m.properties.density_kg_m3 * m.properties.section.area_m2 * length;
        const std::array<int, 2> first{out.dof_of_node[static_cast<std::size_t>(m.first)],
                                       out.dof_of_node[static_cast<std::size_t>(m.second)]};
        for (int i = 0; i < 12; ++i) {
            const int gi = first[static_cast<std::size_t>(i / 6)];
            if (gi < 0) continue;
            for (int j = 0; j < 12; ++j) {
                const int gj = first[static_cast<std::size_t>(j / 6)];
                if (gj < 0) continue;
                out.stiffness(gi + i % 6, gj + j % 6) += k_global(i, j);
                out.mass(gi + i % 6, gj + j % 6) += m_global(i, j);
            }
        }
    }
    // The instrument's load: a rigid block, its centre of gravity above the adapter's node.
    const double load_mass = kPrimaryMassKg - out.frame_mass_kg;
    const Vector3d inertia = load_mass / 12.0 *
                             Vector3d(kLoadSideY * kLoadSideY + kLoadHeight * kLoadHeight,
                                      kLoadSideX * kLoadSideX + kLoadHeight * kLoadHeight,
                                      kLoadSideX * kLoadSideX + kLoadSideY * kLoadSideY);
    const int l = out.dof_of_node[static_cast<std::size_t>(f.load_node)];
    out.mass.block<6, 6>(l, l) +=
        sb::structure::rigid_body_mass(load_mass, inertia, Vector3d(0.0, 0.0, 0.5 * kLoadHeight));
    return out;
}

struct ModeSummary {
    double frequency_hz;
    Vector3d effective_mass_kg;  ///< along x, y, z
};

std::vector<ModeSummary> modes(const Frame& f, const Matrices& m, int count) {
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(m.stiffness, m.mass);
    MatrixXd rigid = MatrixXd::Zero(m.mass.rows(), 3);
    for (std::size_t i = 0; i < f.nodes.size(); ++i) {
        const int d = m.dof_of_node[i];
        if (d < 0) continue;
        for (int a = 0; a < 3; ++a) rigid(d + a, a) = 1.0;
    }
    std::vector<ModeSummary> out;
    for (int k = 0; k < count && k < eig.eigenvalues().size(); ++k) {
        const Eigen::VectorXd phi = eig.eigenvectors().col(k);
        const double gen = phi.dot(m.mass * phi);
        const Eigen::Vector3d l = rigid.transpose() * (m.mass * phi);
        out.push_back(
            {std::sqrt(eig.eigenvalues()(k)) / (2.0 * std::numbers::pi), l.cwiseProduct(l) / gen});
    }
    return out;
}

/// The first three modes of the YZ plane (the frame is symmetric in X: a Z base motion excites
/// only them), those with an effective mass along Y or Z above 2 % of the total.
std::array<double, 3> yz_frequencies(const Sizes& s) {
    const Frame f = build_frame(s);
    const Matrices m = assemble(f);
    std::array<double, 3> out{};
    std::size_t found = 0;
    for (const auto& mode : modes(f, m, 30)) {
        if (mode.effective_mass_kg.y() + mode.effective_mass_kg.z() < 0.02 * kPrimaryMassKg)
            continue;
        out[found++] = mode.frequency_hz;
        if (found == 3) break;
    }
    return out;
}

/// Model update: Newton on the logarithms of the three sizes to the three target frequencies
/// (the finite-difference Jacobian of log f against log size).
Sizes update_sizes(Sizes s, const std::array<double, 3>& target_hz) {
    auto as_vector = [](const Sizes& z) {
        return Eigen::Vector3d(std::log(z.leg_thickness_m), std::log(z.leg_width_m),
                               std::log(z.adapter_side_m));
    };
    auto as_sizes = [](const Eigen::Vector3d& v) {
        return Sizes{std::exp(v(0)), std::exp(v(1)), std::exp(v(2))};
    };
    auto residual = [&](const Eigen::Vector3d& v) {
        const auto f = yz_frequencies(as_sizes(v));
        Eigen::Vector3d r;
        for (int i = 0; i < 3; ++i) r(i) = std::log(f[i] / target_hz[i]);
        return r;
    };
    Eigen::Vector3d v = as_vector(s);
    for (int iteration = 0; iteration < 40; ++iteration) {
        const Eigen::Vector3d r = residual(v);
        if (r.cwiseAbs().maxCoeff() < 1e-7) break;
        Eigen::Matrix3d j;
        for (int k = 0; k < 3; ++k) {
            Eigen::Vector3d h = v;
            h(k) += 1e-4;
            j.col(k) = (residual(h) - r) / 1e-4;
        }
        Eigen::Vector3d step = j.colPivHouseholderQr().solve(-r);
        if (step.cwiseAbs().maxCoeff() > 0.3) step *= 0.3 / step.cwiseAbs().maxCoeff();
        v += step;
    }
    return as_sizes(v);
}

/// The updated model: sizes, assembled matrices and the modes below 2 kHz.
struct Bracket {
    Sizes sizes;
    Frame frame;
    Matrices matrices;
};

/// The paper's first mode and the centres of its two upper Z resonance regions [Hz].
constexpr std::array<double, 3> kTargetHz{239.0, 1170.0, 1575.0};

Bracket updated_bracket() {
    Bracket b;
    b.sizes = update_sizes(Sizes{}, kTargetHz);
    b.frame = build_frame(b.sizes);
    b.matrices = assemble(b.frame);
    const auto f = yz_frequencies(b.sizes);
    for (std::size_t i = 0; i < f.size(); ++i)
        if (std::abs(f[i] / kTargetHz[i] - 1.0) > 1e-6)
            throw std::runtime_error("the model update did not reach the target frequencies");
    return b;
}

/// The rigid translations: column d holds 1 at every node's translation along d.
MatrixXd rigid_translations(const Bracket& b) {
    MatrixXd r = MatrixXd::Zero(b.matrices.mass.rows(), 3);
    for (int d : b.matrices.dof_of_node)
        if (d >= 0)
            for (int a = 0; a < 3; ++a) r(d + a, a) = 1.0;
    return r;
}

/// Matrix Market coordinate text: the lower triangle of a symmetric matrix, or every entry of
/// a general one; exact zeros left out.
std::string matrix_market(const MatrixXd& a, bool symmetric) {
    std::ostringstream body;
    long entries = 0;
    body.precision(17);
    for (Eigen::Index j = 0; j < a.cols(); ++j)
        for (Eigen::Index i = symmetric ? j : 0; i < a.rows(); ++i)
            if (a(i, j) != 0.0) {
                body << i + 1 << ' ' << j + 1 << ' ' << a(i, j) << '\n';
                ++entries;
            }
    std::ostringstream out;
    out << "%%MatrixMarket matrix coordinate real " << (symmetric ? "symmetric" : "general")
        << "\n% paper 001 bracket: shakerbench-paper001-bracket (apps/paper001_bracket.cpp)\n"
        << a.rows() << ' ' << a.cols() << ' ' << entries << '\n'
        << body.str();
    return out.str();
}

struct OutputFile {
    std::string name;
    MatrixXd matrix;
    bool symmetric;
};

std::vector<OutputFile> output_files(const Bracket& b) {
    // The matrices in their symmetric part: assembly sums equal terms in another order.
    const MatrixXd m = 0.5 * (b.matrices.mass + b.matrices.mass.transpose());
    const MatrixXd k = 0.5 * (b.matrices.stiffness + b.matrices.stiffness.transpose());
    return {{"bracket_mass.mtx", m, true},
            {"bracket_stiffness.mtx", k, true},
            {"bracket_rigid.mtx", rigid_translations(b), false}};
}

void print_summary(const Bracket& b) {
    std::printf(
        "updated sizes: legs %.2f mm thick (Y) x %.2f mm wide (X), adapter %.2f mm square\n",
        1e3 * b.sizes.leg_thickness_m, 1e3 * b.sizes.leg_width_m, 1e3 * b.sizes.adapter_side_m);
    std::printf("frame %.3f kg + load %.3f kg = %.3f kg, %ld DOFs\n", b.matrices.frame_mass_kg,
                kPrimaryMassKg - b.matrices.frame_mass_kg, kPrimaryMassKg,
                static_cast<long>(b.matrices.mass.rows()));
    std::printf("mode  frequency [Hz]  effective mass x, y, z [kg]\n");
    int index = 0;
    for (const auto& mode : modes(b.frame, b.matrices, 12)) {
        if (mode.frequency_hz > 2000.0) break;
        std::printf("%4d  %14.1f  %7.3f %7.3f %7.3f\n", ++index, mode.frequency_hz,
                    mode.effective_mass_kg.x(), mode.effective_mass_kg.y(),
                    mode.effective_mass_kg.z());
    }
    std::printf("[structure.matrix.dofs]\n");
    for (const auto& [name, node] : b.frame.named_nodes) {
        const int d = b.matrices.dof_of_node[static_cast<std::size_t>(node)];
        const char* axes[] = {"x", "y", "z", "rx", "ry", "rz"};
        for (int a = 0; a < 6; ++a) std::printf("\"%s.%s\" = %d\n", name.c_str(), axes[a], d + a);
    }
}

/// Every committed file equal to what the generator builds, entry by entry to a relative
/// 1e-12 of the matrix's largest entry (the text may differ in its last digit across
/// compilers).
bool check(const Bracket& b, const std::filesystem::path& dir) {
    bool same = true;
    for (const auto& file : output_files(b)) {
        const auto path = dir / file.name;
        try {
            const MatrixXd committed = sb::structure::read_matrix_market_dense(path);
            const double scale = file.matrix.cwiseAbs().maxCoeff();
            if (committed.rows() != file.matrix.rows() || committed.cols() != file.matrix.cols() ||
                (committed - file.matrix).cwiseAbs().maxCoeff() > 1e-12 * scale) {
                std::fprintf(stderr, "%s: differs from the model the generator builds\n",
                             path.string().c_str());
                same = false;
            }
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s\n", e.what());
            same = false;
        }
    }
    return same;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string usage =
        "usage: shakerbench-paper001-bracket [--write DIR | --check DIR]\n"
        "  prints the updated bracket model; --write writes bracket_{mass,stiffness,rigid}.mtx\n"
        "  into DIR, --check exits 1 unless DIR holds them as built\n";
    if (argc != 1 && argc != 3) {
        std::fputs(usage.c_str(), stderr);
        return 2;
    }
    try {
        const Bracket b = updated_bracket();
        if (argc == 1) {
            print_summary(b);
            return 0;
        }
        const std::string mode = argv[1];
        const std::filesystem::path dir = argv[2];
        if (mode == "--check") return check(b, dir) ? 0 : 1;
        if (mode != "--write") {
            std::fputs(usage.c_str(), stderr);
            return 2;
        }
        for (const auto& file : output_files(b)) {
            std::ofstream out(dir / file.name);
            out << matrix_market(file.matrix, file.symmetric);
            if (!out) throw std::runtime_error((dir / file.name).string() + ": cannot be written");
        }
        print_summary(b);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "shakerbench-paper001-bracket: %s\n", e.what());
        return 1;
    }
}

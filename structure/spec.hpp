// What a structure is made of, in SI, as the config layer hands it to the structure module.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/violation.hpp"

namespace sb::structure {

/// Beam frame: x along the beam axis from the root, y along the section's longer side
/// (stiff bending), z along the shorter side (weak bending: the shaker direction).

enum class SupportKind {
    clamped,  ///< all six DOFs fixed
    pinned,   ///< translations and torsion fixed, bending rotations free
    free,     ///< nothing fixed
    elastic,  ///< three translational and three rotational springs to ground
};
inline constexpr std::pair<SupportKind, std::string_view> kSupportKindNames[] = {
    {SupportKind::clamped, "clamped"},
    {SupportKind::pinned, "pinned"},
    {SupportKind::free, "free"},
    {SupportKind::elastic, "elastic"}};

struct Support {
    std::string name;  ///< e.g. "root", "tip"
    double x_m = 0.0;  ///< position along the beam [m]
    SupportKind kind = SupportKind::clamped;
    Eigen::Vector3d translational_stiffness_n_per_m = Eigen::Vector3d::Zero();  ///< elastic only
    Eigen::Vector3d rotational_stiffness_nm_per_rad = Eigen::Vector3d::Zero();  ///< elastic only
};

/// A named point on the beam axis (sensor, load cell, shaker, damper): the mesh has a node there.
struct NamedPoint {
    std::string name;
    double x_m = 0.0;  ///< position along the beam [m]
};

/// A rigid lumped mass attached to the node at a named point (or at x_m), its centre of
/// gravity at offset_m from the beam axis, with rotary inertia about its own centre of gravity
/// (principal axes = beam frame).
struct LumpedMass {
    std::string name;      ///< label; empty: the name of its point
    std::string point;     ///< the named point it sits at; empty: at x_m
    double x_m = 0.0;      ///< position when no point is named [m]
    double mass_kg = 0.0;  ///< [kg]
    Eigen::Vector3d inertia_kg_m2 = Eigen::Vector3d::Zero();  ///< [kg m^2] about x, y, z
    Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();       ///< [m] CG offset from axis
};

/// Straight prismatic beam with a rectangular section.
struct BeamSpec {
    double length_m = 0.0;
    double width_m = 0.0;      ///< section side along y (the longer one) [m]
    double thickness_m = 0.0;  ///< section side along z (the shorter one, shaker direction) [m]
    double density_kg_m3 = 0.0;
    double youngs_modulus_pa = 0.0;
    std::optional<double>
        shear_modulus_pa;   ///< given: Timoshenko elements; absent: Euler-Bernoulli
    int min_elements = 40;  ///< the mesh has at least this many elements
    std::vector<Support> supports;
    std::vector<NamedPoint> points;
    std::vector<LumpedMass> masses;

    /// Every violated constraint (keys relative to the beam section of the config).
    [[nodiscard]] Violations validate() const;
    /// A copy with every mass given by its point placed at that point and, without a name of
    /// its own, named after it: the positions as the model uses them, whatever the points
    /// were changed to after reading. A point that does not exist leaves x_m (validate()
    /// reports it).
    [[nodiscard]] BeamSpec resolved() const;
};

/// A chain or network of point masses moving along the excitation direction (papers 003, 004).
struct LumpedSpec {
    struct Mass {
        std::string name;
        double mass_kg = 0.0;
    };
    /// A spring-dashpot between two masses, or between a mass and "ground".
    struct Spring {
        std::string from;
        std::string to;
        double stiffness_n_per_m = 0.0;
        double damping_n_s_per_m = 0.0;
    };
    std::vector<Mass> masses;
    std::vector<Spring> springs;

    [[nodiscard]] Violations validate() const;
};

/// A rigid mass added at a named point of an imported model (an enclosure, a sensor, a rigid
/// damper, a mounting block, the shaker's armature), its centre of gravity at offset_m from the
/// point, with rotary inertia about its own centre of gravity (principal axes = structure
/// frame). Offset and inertia act only through the point's rotation DOFs, when it has them.
struct PointMass {
    std::string name;      ///< label; empty: the name of its point
    std::string point;     ///< the named point it is attached to
    double mass_kg = 0.0;  ///< [kg]
    Eigen::Vector3d inertia_kg_m2 = Eigen::Vector3d::Zero();  ///< [kg m^2] about x, y, z
    Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();       ///< [m] CG offset from the point
};

/// Mass and stiffness matrices from Matrix Market files with named DOFs (paper 001's bracket).
struct MatrixSpec {
    std::filesystem::path mass_file;
    std::filesystem::path stiffness_file;
    /// Named DOFs: name -> zero-based row index. A named point "p" is made of the DOFs named
    /// "p.x", "p.y", "p.z" (and optionally "p.rx", "p.ry", "p.rz"), whichever exist.
    std::vector<std::pair<std::string, int>> named_dofs;
    /// Optional n x 3 Matrix Market file: column d holds the DOF values of a unit rigid
    /// translation along axis d (for effective masses). Without it the rigid translations are
    /// built from the named DOFs, which is only complete when every row is named.
    std::filesystem::path rigid_body_file;
    /// Optional n x 1 Matrix Market file for base excitation: the influence vector r, every
    /// DOF's displacement per unit base displacement along the excitation direction. Without
    /// it r is the rigid translation along that direction.
    std::filesystem::path base_influence_file;
    /// Optional n x n Matrix Market file: a physical damping matrix C [N s/m, ...] on the same
    /// DOFs (joints, dashpots, a damping model built with the import). It replaces
    /// [structure.damping]: each mode's ratio is phi^T C phi / (2 omega) (the reduced modal
    /// model keeps the diagonal of Phi^T C Phi, the full model C itself).
    std::filesystem::path damping_file;
    /// Rigid masses added at named points (from the config, and those the bench adds).
    std::vector<PointMass> masses;

    [[nodiscard]] Violations validate() const;
    /// The point a DOF name belongs to: "p" for "p.x", "p.y", "p.z", "p.rx", "p.ry", "p.rz";
    /// the whole name otherwise (a point moving along the excitation direction).
    [[nodiscard]] static std::string point_of(const std::string& dof);
};

/// Modal damping ratios per mode, or Rayleigh damping C = alpha M + beta K.
struct DampingSpec {
    enum class Model { modal, rayleigh };
    static constexpr std::pair<Model, std::string_view> kModelNames[] = {
        {Model::modal, "modal"}, {Model::rayleigh, "rayleigh"}};
    Model model = Model::modal;
    double default_ratio = 0.005;      ///< modal: ratio of every mode not listed [-]
    std::vector<double> modal_ratios;  ///< modal: ratios of modes 1, 2, ... [-]
    double alpha_per_s = 0.0;          ///< rayleigh: mass-proportional coefficient [1/s]
    double beta_s = 0.0;               ///< rayleigh: stiffness-proportional coefficient [s]

    [[nodiscard]] Violations validate() const;
    /// Damping ratio of a mode (1-based index) with circular frequency omega_rad_s.
    [[nodiscard]] double ratio(int mode, double omega_rad_s) const;
};

/// How the structure is driven.
struct ExcitationSpec {
    enum class Kind { force, base };
    static constexpr std::pair<Kind, std::string_view> kKindNames[] = {{Kind::force, "force"},
                                                                       {Kind::base, "base"}};
    Kind kind = Kind::force;
    std::string point;  ///< force: named point the force acts at
    /// base: the support that moves (beam: a support's name; lumped: "ground"); empty for an
    /// imported model, whose base DOFs were constrained out of its matrices.
    std::string support;
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit vector, structure frame

    [[nodiscard]] Violations validate() const;
};

struct StructureSpec {
    enum class Kind { beam, lumped, matrix };
    static constexpr std::pair<Kind, std::string_view> kKindNames[] = {
        {Kind::beam, "beam"}, {Kind::lumped, "lumped"}, {Kind::matrix, "matrix"}};
    Kind kind = Kind::beam;
    BeamSpec beam;
    LumpedSpec lumped;
    MatrixSpec matrix;
    DampingSpec damping;
    ExcitationSpec excitation;
    int modes = 6;                                     ///< modes kept in the reduced modal model
    Eigen::Vector3d gravity_m_s2{0.0, 0.0, -9.80665};  ///< structure frame

    [[nodiscard]] Violations validate() const;
};

}  // namespace sb::structure

// Typed option structs of the DEM module (SI units, documented defaults, validate()).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "core/units.hpp"
#include "core/violation.hpp"

namespace sb::dem {

/// Elastic material of the particles or of the walls.
struct Material {
    double density_kg_m3 = 7800.0;     ///< mass density [kg/m^3] (steel)
    double youngs_modulus_pa = 210e9;  ///< Young's modulus [Pa] (used by Hertz)
    double poisson_ratio = 0.3;        ///< Poisson ratio [-] (used by Hertz)
    Violations validate() const;
};

/// Contact properties of one pair type (particle–particle or particle–wall).
struct PairProperties {
    double restitution = 0.9;        ///< normal coefficient of restitution [-], in (0, 1]
    double sliding_friction = 0.6;   ///< Coulomb sliding friction coefficient [-] (paper 000)
    double rolling_friction = 0.01;  ///< rolling friction coefficient mu_r [-] (paper 000)
    /// Viscoelastic damping only: the dissipative constant A of F_d = 3/2 A k sqrt(delta)
    /// delta_dot (Brilliantov et al. 1996), whose restitution falls with the impact speed [s].
    double dissipative_constant_s = 0.0;
    /// Viscous damping only: the dashpot coefficient c of F_d = c delta_dot [N s/m].
    double dashpot_n_s_per_m = 0.0;
    Violations validate() const;
};

/// One class of a discrete size distribution.
struct SizeFraction {
    double diameter_m = 3e-3;      ///< sphere diameter [m]
    double number_fraction = 1.0;  ///< share of the particle count [-]
};

/// Largest relative standard deviation of the diameters about their nominal value [-].
inline constexpr double kMaxDiameterScatter = 0.2;

/// The particle population.
struct ParticleOptions {
    int count = 120;                                ///< number of spheres
    double diameter_m = 3e-3;                       ///< diameter when monodisperse [m]
    std::vector<SizeFraction> size_distribution{};  ///< if non-empty, replaces diameter_m
    /// Relative standard deviation s of every sphere's diameter about its nominal value (a
    /// manufacturing tolerance, wear) [-]: nominal (1 + s u), u uniform in [-sqrt 3, sqrt 3]
    /// (make_radii); 0 = every sphere its nominal size.
    double diameter_scatter = 0.0;
    Material material{};  ///< particle material
    Violations validate() const;
    /// The largest diameter a sphere can have, scatter included: the largest nominal one
    /// times 1 + sqrt(3) s [m].
    double largest_diameter_m() const;
    /// The smallest diameter a sphere can have: the smallest nominal one times 1 - sqrt(3) s
    /// [m]. Its contacts are the shortest, so it sets the time step.
    double smallest_diameter_m() const;
};

enum class NormalLaw { hooke, hertz };
/// `restitution` picks the dashpot that matches the normal law.
enum class DampingLaw { none, restitution, linear_dashpot, hertz_dashpot, viscoelastic, viscous };
enum class TangentialLaw { none, directional_coulomb, coulomb_spring };
enum class RollingLaw { none, constant_torque };

/// Composition and coefficients of the contact law (style.md: fixed slots).
struct ContactOptions {
    NormalLaw normal = NormalLaw::hooke;
    DampingLaw damping = DampingLaw::restitution;
    TangentialLaw tangential = TangentialLaw::directional_coulomb;
    RollingLaw rolling = RollingLaw::constant_torque;
    /// Hooke: spring constant [N/m] (required > 0). Hertz: k in k*delta^1.5 [N/m^1.5]; 0 means
    /// from the materials, k = 4/3 E* sqrt(R*).
    double normal_stiffness = 0.0;
    /// Hooke only: wall spring constant [N/m]; 0 means the same as normal_stiffness.
    double wall_normal_stiffness = 0.0;
    /// CoulombSpring: tangential stiffness as a fraction of the (tangent) normal stiffness [-].
    double tangential_stiffness_ratio = 2.0 / 7.0;
    /// DirectionalCoulomb/rolling: slip speed below which the force ramps linearly to 0 [m/s].
    double slip_regularisation_m_s = 1e-4;
    PairProperties particle_particle{};
    PairProperties particle_wall{};
    Material wall_material{};  ///< enclosure material (Hertz walls)
    /// Particle-side coefficients where the lateral surface (the cylinder's mantle, the box's
    /// four faces along its axis) is not of the ends' material (paper 000: a PMMA tube
    /// between aluminium ends); absent: the particle-wall ones.
    std::optional<PairProperties> particle_side;
    std::optional<Material> side_material;  ///< lateral surface material; absent: wall_material
    /// Particle-rod coefficients of the obstacle grid, whose lattice need not be of the walls'
    /// material (paper 002's 3.3 g grid is a printed lattice, its shell metal); absent: the
    /// particle-wall ones.
    std::optional<PairProperties> particle_rod;
    std::optional<Material> rod_material;  ///< rod material (Hertz); absent: wall_material
    Violations validate() const;
};

enum class EnclosureShape { cylinder, box };
inline constexpr std::pair<EnclosureShape, std::string_view> kEnclosureShapeNames[] = {
    {EnclosureShape::cylinder, "cylinder"}, {EnclosureShape::box, "box"}};

/// Rods of diameter rod_diameter_m along every edge of a cubic cell lattice (paper 002).
struct RodGridOptions {
    bool enabled = false;
    double rod_diameter_m = 1e-3;             ///< rod diameter [m]
    double cell_size_m = 5e-3;                ///< lattice spacing [m]
    Eigen::Vector3d origin_m{0.0, 0.0, 0.0};  ///< one lattice node, enclosure frame [m]
    Violations validate() const;
};

/// A solid axis-aligned plate (partition rib) in the enclosure frame.
struct PlateOptions {
    Eigen::Vector3d min_corner_m{0.0, 0.0, 0.0};  ///< [m]
    Eigen::Vector3d max_corner_m{0.0, 0.0, 0.0};  ///< [m]
};

/// The cavity in its own frame: axis along local z, bottom at z = 0, centred on the z axis.
/// The frame origin (bottom centre) is the reference point for the wall moment.
struct EnclosureOptions {
    EnclosureShape shape = EnclosureShape::cylinder;
    double inner_diameter_m = 19e-3;  ///< cylinder inner diameter [m] (paper 000 Table 1)
    double height_m = 25e-3;          ///< inner height (cylinder and box) [m]
    double length_x_m = 30e-3;        ///< box inner size along local x [m] (paper 002)
    double length_y_m = 30e-3;        ///< box inner size along local y [m]
    RodGridOptions rods{};
    std::vector<PlateOptions> plates{};
    Violations validate() const;
};

/// Particles that move with the enclosure until a release time (paper 004's electromagnet
/// holds the granules; a weaker current frees a share of them).
struct LockOptions {
    std::vector<int> particle_ids{};  ///< explicit set (enclosure-frame positions are frozen)
    double fraction = 0.0;            ///< else this share, lowest along local z first [-]
    /// Solver time at which locked particles are freed [s]; 0 = never (they stay locked).
    double release_time_s = 0.0;
    /// Share of all particles freed then, the highest locked along local z first (farthest
    /// from a magnet at the bottom), the rest staying locked; 1: every locked one [-].
    double release_fraction = 1.0;
    Violations validate() const;
};

/// The smallest Verlet skin an adapting solver takes, as a share of the configured one [-].
inline constexpr double kMinSkinShare = 0.1;

/// Everything the solver needs.
struct SolverOptions {
    ParticleOptions particles{};
    ContactOptions contact{};
    EnclosureOptions enclosure{};
    LockOptions lock{};
    Eigen::Vector3d gravity_m_s2{0.0, 0.0, -kStandardGravity};  ///< world frame [m/s^2]
    double max_overlap_fraction = 0.5;  ///< guard: overlap / radius above this throws [-]
    /// Verlet skin of the broad phase as a fraction of the largest diameter [-]; the list is
    /// rebuilt when a particle has moved more than half the skin in the enclosure frame
    /// (0 = rebuild every step). With adapt_neighbor_skin, the largest skin the solver uses.
    double neighbor_skin_fraction = 0.1;
    /// Choose the skin at each rebuild, between kMinSkinShare of neighbor_skin_fraction and
    /// neighbor_skin_fraction, so that the candidate tests the skin adds cost about what the
    /// rebuilds cost (Solver::build_neighbors). The lists hold every touching pair whatever the
    /// skin and are sorted by partner, so results are bitwise the same as with a fixed skin.
    bool adapt_neighbor_skin = true;
    int threads = 1;  ///< OpenMP threads; 0 = OpenMP default
    /// Smallest number of particles per thread: every per-step loop (local positions, the
    /// contact sweep, the broad phase) runs on min(threads, N / parallel_grain) threads, so
    /// that small dampers run with no OpenMP region at all (its fixed cost, several us, would
    /// exceed the gain). Results do not depend on it; lower it to exercise the parallel path.
    int parallel_grain = 512;
    bool track_energy = true;  ///< energy ledger each step
    int energy_layers = 0;     ///< dissipation per horizontal layer (along gravity; 0 = off)
    Violations validate() const;
};

}  // namespace sb::dem

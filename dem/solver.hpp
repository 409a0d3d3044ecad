// The DEM solver: spheres in a moving rigid enclosure, semi-implicit Euler, wall force/moment.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem/contact_law.hpp"
#include "dem/enclosure.hpp"
#include "dem/options.hpp"
#include "dem/solver_state.hpp"

namespace sb::dem {

/// A run-time guard fired (NaN, excessive overlap, particle outside the enclosure).
class SimulationError : public std::runtime_error {
  public:
    enum class Kind { not_finite, overlap, outside };
    SimulationError(Kind kind, std::int64_t step, double time_s, int particle_id,
                    const std::string& what);
    Kind kind;
    std::int64_t step;  ///< step index at which the guard fired
    double time_s;      ///< simulated time [s]
    int particle_id;    ///< offending particle (lowest id if several)
};

/// Initial particles: positions and velocities in the enclosure frame.
struct ParticleSet {
    std::vector<Eigen::Vector3d> positions_m{};     ///< centres, enclosure frame [m]
    std::vector<double> radii_m{};                  ///< [m]
    std::vector<Eigen::Vector3d> velocities_m_s{};  ///< relative to the enclosure (optional)
    std::vector<Eigen::Vector3d> angular_velocities_rad_s{};  ///< (optional)
};

/// The particles of a SolverState in the enclosure frame of state.enclosure, as
/// Solver::local_snapshot() gives them (spins in enclosure axes, not relative to the
/// enclosure). Throws std::invalid_argument if the arrays differ in length.
ParticleSet local_particles(const SolverState& state);

/// Struct-of-arrays particle state, world frame.
struct ParticleState {
    std::vector<Eigen::Vector3d> x;    ///< positions [m]
    std::vector<Eigen::Vector3d> v;    ///< velocities [m/s]
    std::vector<Eigen::Vector3d> w;    ///< angular velocities [rad/s]
    std::vector<double> radius;        ///< [m]
    std::vector<double> inv_mass;      ///< [1/kg]
    std::vector<double> inv_inertia;   ///< [1/(kg m^2)]
    std::vector<std::uint8_t> locked;  ///< 1 while moving with the enclosure
    std::size_t size() const { return x.size(); }
};

/// Energy ledger [J]. Works are cumulative since construction (or reset_energy()); the state
/// energies are current. balance_error() = W_walls - (E - E0) - dissipated.
struct EnergyLedger {
    double wall_work = 0.0;       ///< work done by the walls on the particles
    double normal_damping = 0.0;  ///< dissipated by the normal dashpots
    double friction = 0.0;        ///< dissipated by sliding friction (incl. spring storage)
    double rolling = 0.0;         ///< dissipated by rolling resistance
    double kinetic_translational = 0.0;
    double kinetic_rotational = 0.0;
    double potential = 0.0;      ///< -m g.x, world frame
    double elastic = 0.0;        ///< stored in the normal springs
    double initial_total = 0.0;  ///< total mechanical energy at the last reset
    /// Per horizontal layer, bottom first: slabs normal to gravity at the initial pose
    /// (Solver::layers(), paper 002 Fig. 13).
    std::vector<double> layer_dissipation{};
    /// Per horizontal layer (the one holding the sphere's centre): the time integral of the
    /// kinetic energy of the particles' motion relative to the enclosure, translation and
    /// spin, sampled after every step [J s]. Its change over an interval divided by the
    /// interval's length is the layer's mean agitation: zero for a bed riding its enclosure
    /// rigidly, whatever the enclosure does (paper 000, section 4: which layers move).
    std::vector<double> layer_kinetic_time{};

    double mechanical() const {
        return kinetic_translational + kinetic_rotational + potential + elastic;
    }
    double dissipated() const { return normal_damping + friction + rolling; }
    double balance_error() const {
        return wall_work - (mechanical() - initial_total) - dissipated();
    }
};

/// DEM solver driven by the bench: set_enclosure_state() -> step(dt) -> wall_force/moment.
class Solver {
  public:
    /// Throws std::invalid_argument listing every violation of options.validate().
    Solver(const SolverOptions& options, const ParticleSet& particles,
           const EnclosureState& enclosure = {});
    /// Continues a saved state with the enclosure at `enclosure`. At state.enclosure (bitwise
    /// the same pose and velocity) the run continues bitwise identically to the solver the
    /// state was taken from, whenever its neighbour list was built. At another pose the bed
    /// moves rigidly with the enclosure: the particles as Solver(options,
    /// local_particles(state), enclosure) places them, the springs turned by R_new R_old^T.
    /// The lock comes from the state (options.lock only gives the release time), the clock
    /// continues from state.time_s; the springs are used by coulomb_spring only. The energy
    /// ledger starts afresh, as after construction, and wall_force() reads 0 until a step.
    /// Throws std::invalid_argument for options or a state that do not fit together.
    Solver(const SolverOptions& options, const SolverState& state, const EnclosureState& enclosure);

    /// Pose and velocity of the enclosure at the start of the next step.
    void set_enclosure_state(const EnclosureState& state);
    const EnclosureState& enclosure_state() const { return enclosure_state_; }

    /// One semi-implicit Euler step of dt [s]. Throws SimulationError if a guard fires; the
    /// particles have then already been advanced (the run cannot continue).
    void step(double dt);

    /// Force exerted by the particles on the enclosure during the last step, world [N].
    const Eigen::Vector3d& wall_force() const { return wall_force_; }
    /// Moment of that force about the enclosure origin, world [N m].
    const Eigen::Vector3d& wall_moment() const { return wall_moment_; }

    EnergyLedger energy() const;
    /// Energy dissipated since the last reset (normal dashpots, friction, rolling) [J]: the
    /// cumulative part of energy() without its O(N + contacts) pass, for sampling every step.
    double dissipated_j() const { return ledger_.dissipated(); }
    /// Restarts the cumulative works and the reference energy.
    void reset_energy();
    /// Takes the cumulative works and the reference energy of `saved` (a ledger this run's
    /// solver gave before it was saved), so that a solver restored from a SolverState keeps
    /// its ledger: a run continued from a checkpoint adds the same steps' works to the same
    /// sums as the uninterrupted one. Throws std::invalid_argument when the ledger's layers
    /// are not options.energy_layers.
    void continue_energy(const EnergyLedger& saved);
    /// Kinetic energy of the particles relative to the enclosure's rigid motion, translation
    /// and spin [J]: the bed's agitation, without the 1/2 m v_wall^2 every particle riding
    /// along would carry. O(particles).
    double relative_kinetic_energy() const;

    const ParticleState& particles() const { return state_; }
    /// Positions and velocities in the enclosure frame (for saving a settled state).
    ParticleSet local_snapshot() const;
    /// Everything needed to continue this run exactly (see SolverState).
    SolverState state() const;
    double time() const { return time_; }
    std::int64_t step_count() const { return step_; }
    /// Contacts (pairs and walls) of the last step.
    std::size_t contact_count() const { return contact_count_; }
    /// Number of neighbour-list (broad phase) rebuilds so far.
    std::int64_t neighbor_builds() const { return neighbor_builds_; }
    /// Verlet skin of the current neighbour list [m] (SolverOptions::adapt_neighbor_skin).
    double neighbor_skin() const { return skin_; }
    const ContactLaw& law() const { return law_; }
    const Enclosure& enclosure() const { return enclosure_; }
    /// The energy_layers slabs along gravity, fixed in the enclosure frame at the pose the
    /// solver was built with.
    const HorizontalLayers& layers() const { return layers_; }
    const SolverOptions& options() const { return options_; }
    /// Pair coefficients after set-up (for logging): [0] particle-particle, [1] particle-wall
    /// (the ends), [2] particle-rod, [3] particle-side (the lateral surface).
    const PairCoefficients& coefficients(int which) const { return coeff_[which]; }

    /// Locks particles to the enclosure (frozen enclosure-frame positions) until release().
    void lock(const std::vector<int>& ids);
    void release();
    /// Frees `count` locked particles, the highest along the enclosure's z first (all when
    /// count >= locked_count()).
    void release(int count);
    int locked_count() const;
    /// True once locked particles were freed (and none locked since); some may stay locked
    /// after a partial release (LockOptions::release_fraction).
    bool released() const { return released_; }

    /// The locked particles as one rigid body, in the enclosure frame.
    struct LockedBody {
        double mass_kg = 0.0;
        Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< centre of gravity
        /// Inertia tensor about the centre of gravity, enclosure axes [kg m^2].
        Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();
    };
    LockedBody locked_body() const;
    /// True: whoever moves the enclosure carries the locked particles' inertia in its own
    /// mass (a structure with them as rigid mass), so the wall force leaves out the force
    /// that accelerates them with the enclosure. What remains is their weight and the
    /// contact forces they pass on. Loose coupling, which applies a load one step late,
    /// cannot carry a locked bed heavier than the modal mass at its point: the lagging
    /// inertia grows by a factor m_bed / m_modal every step.
    void set_locked_inertia_external(bool external) { locked_inertia_external_ = external; }

    /// Most threads one solver uses (options.threads above this are capped).
    static constexpr std::size_t kMaxChunks = 64;

  private:
    Solver(const SolverOptions& options, const ParticleSet& particles,
           const EnclosureState& enclosure, bool lock_from_options);
    /// The state's springs, lock, clock and exact world values (constructor from a state).
    void restore(const SolverState& state);

    /// What pair slot q of i's Verlet list hands to its partner j.
    struct PairShare {
        Eigen::Vector3d f{0, 0, 0};   ///< force on i (j receives -f) [N]
        Eigen::Vector3d tj{0, 0, 0};  ///< torque on j [N m]
    };
    /// One contact of the step, for the energy ledger (filled only when it is on).
    struct EnergyRecord {
        std::uint32_t i = 0, j = 0;  ///< j >= N: wall
        double delta = 0.0;
        Eigen::Vector3d n, f, ti, xc;  ///< normal, force and torque on i, contact point
        double fs = 0.0, fd = 0.0;     ///< spring and (clamped) damping normal force [N]
        double e[4]{};                 ///< wall work, normal damping, friction, rolling [J]
    };
    /// Sums over a particle's own contacts.
    struct Accumulated {
        Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
        /// Force and moment on the walls: zeroed only for a particle near a wall (the wall
        /// tests run), read only for one with wall contacts (wall_count_ > 0).
        Eigen::Vector3d wf, wm;
    };
    /// Per-thread results of a sweep.
    struct SweepLocal {
        std::size_t contacts = 0;
        int outside = std::numeric_limits<int>::max();
        int overlap = std::numeric_limits<int>::max();
        int not_finite = std::numeric_limits<int>::max();
        std::vector<EnergyRecord>* log = nullptr;
    };

    /// For a turned enclosure, local_x_ = every centre in this step's enclosure frame. Returns
    /// the largest squared displacement from x_at_build_ in that frame if
    /// `measure_displacement`, else 0.
    double to_local_frame(bool measure_displacement);
    /// local_x_ for a list build (an axis-aligned enclosure's, which to_local_frame skips).
    void fill_local_x();
    /// Verlet list from local_x_ (the enclosure-frame positions).
    void build_neighbors();
    /// True if a sphere centred at xl certainly touches no wall or obstacle, whatever its
    /// radius (skips the wall tests).
    bool deep_inside(const Eigen::Vector3d& xl) const;
    /// One step's contacts, forces, gather and update.
    template <class Law>
    void sweep(const Law& law, double dt);
    template <class Law>
    Accumulated own_contacts(const Law& law, std::size_t i, double dt, SweepLocal& loc);
    void finish_particle(std::size_t i, const Accumulated& a, double dt, SweepLocal& loc);
    void account_energy(double dt);
    /// Particle i's kinetic energy relative to the enclosure (relative_kinetic_energy()).
    double relative_kinetic_energy(std::size_t i) const;
    /// Size classes of the particles and their mass constants (class_count_ = 0 for more
    /// than kMaxSizeClasses distinct radii).
    void build_size_classes();
    void snap_locked(double dt);
    void add_held_reaction(double dt);
    int thread_count() const;
    std::size_t grain() const { return static_cast<std::size_t>(options_.parallel_grain); }

    SolverOptions options_;
    Enclosure enclosure_;
    ContactLaw law_;
    /// particle-particle, particle-wall (the ends, plates), particle-rod, particle-side
    PairCoefficients coeff_[4];
    EnclosureState enclosure_state_;
    HorizontalLayers layers_;
    Eigen::Vector3d layers_up_ = Eigen::Vector3d::Zero();  ///< what layers_ was built from
    ParticleState state_;
    std::vector<Eigen::Vector3d> local_x_, lock_local_;
    std::vector<double> hertz_r_side_, hertz_r_rod_;  ///< Hertz R* on cylinder side, rods [m]
    /// Effective masses and radius of a contact, per pair of size classes or per class
    /// against a wall (ContactKinematics' m_eff, r_eff, m_t, i_eff).
    struct MassConstants {
        double m_eff = 0.0, r_eff = 0.0, m_t = 0.0, i_eff = 0.0;
    };
    static constexpr std::size_t kMaxSizeClasses = 16;
    std::vector<std::uint8_t> size_class_;  ///< per particle
    std::vector<MassConstants> class_pair_, class_wall_;
    std::size_t class_count_ = 0;
    double time_ = 0.0;
    std::int64_t step_ = 0;
    bool has_history_ = false;
    bool stepped_ = false;  ///< the contact arrays hold a step's contacts
    bool released_ = false;
    int locked_count_ = 0;
    bool locked_inertia_external_ = false;
    /// The enclosure at the last snap of the locked particles (their velocity then).
    EnclosureState snap_enclosure_;
    std::size_t contact_count_ = 0;

    // broad phase: uniform grid in the enclosure frame, Verlet list (j > i, sorted by j)
    Eigen::Vector3d grid_lo_;
    double cell_ = 0.0;
    int dims_[3]{1, 1, 1};
    std::vector<std::uint32_t> cell_of_, cell_start_, cell_items_, cursor_, count_;
    double skin_ = 0.0;      ///< Verlet skin of the current list [m]
    double skin_max_ = 0.0;  ///< the configured skin; the grid's cells are sized for it [m]
    std::int64_t step_at_build_ = 0;
    std::size_t outer_half_ = 0;  ///< candidates of the current list in the outer half of its skin
    void adapt_skin();
    std::vector<std::uint32_t> nbr_begin_, nbr_list_, old_nbr_begin_, old_nbr_list_;
    std::vector<std::vector<std::uint32_t>> nbr_buffers_;
    std::vector<Eigen::Vector3d> x_at_build_;
    std::int64_t neighbor_builds_ = 0;
    std::vector<std::uint32_t> chunk_;  ///< thread t sweeps particles [chunk_[t], chunk_[t+1])

    // pair slots (one per Verlet entry) and the reverse index of the gather
    /// Contact flag of a pair slot; an enum, not a char type, so that its stores cannot alias
    /// the other arrays (which would force the hot loop to reload them).
    enum class PairFlag : std::uint8_t { apart, touching };
    std::vector<PairFlag> pair_active_, old_pair_active_;     ///< in contact this step
    std::vector<Eigen::Vector3d> pair_hist_, old_pair_hist_;  ///< tangential history
    std::vector<PairShare> pair_share_;
    std::vector<double> pair_delta_, pair_kl_;  ///< overlap and law constant (elastic energy)
    std::vector<std::uint32_t> rev_begin_, rev_slot_;
    /// One-thread sweep: the touching slots each particle receives, at its reverse-index
    /// offset (recv_count_ of them), so that its gather skips the slots apart.
    std::vector<std::uint32_t> recv_slot_, recv_count_;
    bool serial_sweep_ = false;

    // wall slots: wall_cap_ per particle, current and previous step (for the history)
    std::size_t wall_cap_ = 0;
    bool has_obstacles_ = false;
    double cylinder_radius_ = 0.0;  ///< 0 for a box
    /// deep_inside() bounds: centre range and squared clearance from the cylinder side
    Eigen::Vector3d deep_lo_ = Eigen::Vector3d::Zero(), deep_hi_ = Eigen::Vector3d::Zero();
    double deep_rho2_ = -1.0;
    bool track_energy_ = true;
    Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
    bool rotated_ = false;  ///< this step's enclosure rotation is not the identity
    std::vector<std::uint32_t> wall_count_, prev_wall_count_, wall_id_, prev_wall_id_;
    std::vector<Eigen::Vector3d> wall_hist_, prev_wall_hist_;
    std::vector<double> wall_delta_, wall_kl_;

    std::vector<Accumulated> own_;         ///< per particle, between the two parallel phases
    std::vector<SweepLocal> sweep_local_;  ///< per thread, reset at every sweep
    std::vector<Eigen::Vector3d> v_old_, w_old_;
    Eigen::Vector3d wall_force_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d wall_moment_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d lock_force_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d lock_moment_ = Eigen::Vector3d::Zero();

    // energy
    EnergyLedger ledger_;
    std::vector<std::vector<EnergyRecord>> logs_;  ///< per thread, in particle order
};

}  // namespace sb::dem

// The structure with its particle dampers, stepped together: loose (staggered) coupling at
// the DEM time step, as in paper 000 section 3.1.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "bench/campaign_spec.hpp"
#include "dem/solver.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/reduced_modal_model.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// A damper attached to a named point: its DEM solver (absent for a rigid damper) and where
/// its enclosure sits relative to the point.
struct MountedDamper {
    std::string name;
    std::string point;
    Eigen::Matrix3d mount_rotation = Eigen::Matrix3d::Identity();  ///< enclosure -> structure
    Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();  ///< enclosure origin from the point
    std::unique_ptr<dem::Solver> solver;                 ///< null for a rigid damper
};

/// The state a sweep carries from one point to the next (and through a checkpoint). Every
/// point starts at its own time 0 (phase 0 of its sine), so no clock is kept.
struct SpecimenState {
    Eigen::VectorXd q;                        ///< modal displacements
    Eigen::VectorXd q_dot;                    ///< modal velocities
    std::vector<dem::ParticleSet> particles;  ///< per damper, enclosure frame
    /// Per damper: the force [N] and moment [N m] it applied at its point in the last step.
    std::vector<Eigen::Matrix<double, 6, 1>> damper_loads;
};

/// Structure + dampers + excitation. Every step: the structure's kinematics at each damper
/// point move its enclosure, the DEM advances, and the wall force and moment (moved to the
/// point) load the structure over the same step.
class CoupledSpecimen {
  public:
    /// `channel_points`: the points whose acceleration along the excitation direction is
    /// recorded (channels "acc_<point>"); the first one is the control channel.
    CoupledSpecimen(const structure::LinearModel& model, const structure::ModalBasis& basis,
                    const structure::ExcitationSpec& excitation, std::vector<MountedDamper> dampers,
                    std::vector<std::string> channel_points, double dt_max_s,
                    int step_multiple = 1);

    /// Names of the recorded channels: the reference ("force" or "base_acc") first, then
    /// "acc_<point>" for each channel point.
    [[nodiscard]] const std::vector<std::string>& channel_names() const { return names_; }

    /// Chooses the step for this frequency: the largest dt <= dt_max with a whole number of
    /// steps per period, a multiple of step_multiple (no leakage in per-period harmonics;
    /// evenly decimated series), keeping the state.
    void set_frequency(double frequency_hz);
    [[nodiscard]] int steps_per_period() const { return steps_per_period_; }
    [[nodiscard]] double frequency_hz() const { return frequency_hz_; }
    [[nodiscard]] double dt_s() const { return dt_s_; }
    [[nodiscard]] double time_s() const;

    /// The linear model whose steady state start_from_linear_steady_state() uses: the
    /// structure with every damper's particles as rigid mass (same free DOFs), so that the
    /// start sits on the loaded structure's resonance. Default: the specimen's own model.
    void set_start_model(const structure::LinearModel& model, const structure::ModalBasis& basis);

    /// Linear steady state at amplitude A [N, or m/s^2 for base excitation] at the current
    /// frequency (of the start model, projected on the specimen's modes), plus the static
    /// deflection under the particles' weight: a sweep starts with no slow start-up transient.
    /// `response_ratio` scales the harmonic state as a phasor, Q -> c Q (q = Re Q,
    /// q_dot = -w Im Q at phase 0): the steady state of a response c times the start
    /// model's, in amplitude and phase (an equivalent mode identified from measured points).
    void start_from_linear_steady_state(double amplitude, double time_s,
                                        std::complex<double> response_ratio = 1.0);

    /// One coupled step at excitation amplitude A; writes the channel values at the end of
    /// the step into `values` (size = channel_names().size()).
    void step(double amplitude, std::vector<double>& values);

    /// State for warm starts and checkpoints; restore() rebuilds the DEM solvers from it and
    /// restarts the point clock at 0. A sweep goes through state() and restore() between every
    /// two points, interrupted or not, so a resumed campaign repeats the same arithmetic.
    [[nodiscard]] SpecimenState state() const;

    /// Modal displacements of the structure now.
    [[nodiscard]] const Eigen::VectorXd& modal_displacement() const;
    /// Scales the structure's response about `q_mean` at the current time: q -> q_mean +
    /// ratio (q - q_mean), q_dot -> ratio q_dot (the particles keep their state). At the start
    /// of a period of a steady harmonic response at amplitude A, with q_mean its mean over the
    /// period, this is the steady state at amplitude ratio A (linear structure). The particles
    /// keep their enclosure-frame positions and relative velocities.
    void scale_response(double ratio, const Eigen::VectorXd& q_mean);
    void restore(const SpecimenState& state);

    [[nodiscard]] const std::vector<MountedDamper>& dampers() const { return dampers_; }

  private:
    /// Takes every DEM damper's wall force and moment of the last step as its point load.
    void apply_damper_loads();
    /// New DEM solvers with these particles (enclosure frame) in the enclosures' current pose.
    void rebuild_solvers(const std::vector<dem::ParticleSet>& local);
    /// Hands damper_loads_ to the structure, summed per point.
    void set_point_loads();
    /// Pose and velocity of a damper's enclosure from the structure's current kinematics.
    [[nodiscard]] dem::EnclosureState enclosure_state(std::size_t damper) const;
    [[nodiscard]] double excitation_value(double amplitude, double time_s) const;
    void set_excitation(double amplitude, double time_s);

    const structure::LinearModel* model_;
    const structure::ModalBasis* basis_;
    const structure::LinearModel* start_model_;
    const structure::ModalBasis* start_basis_;
    structure::ExcitationSpec excitation_;
    std::vector<MountedDamper> dampers_;
    std::vector<int> damper_point_index_;
    std::vector<Eigen::Matrix<double, 6, 1>> damper_loads_;  ///< last applied, per damper
    std::vector<std::string> channel_points_;
    std::vector<int> channel_index_;
    std::vector<std::string> names_;
    Eigen::Vector3d direction_;
    double dt_max_s_;
    int step_multiple_;
    double frequency_hz_ = 0.0;
    double dt_s_ = 0.0;
    int steps_per_period_ = 0;
    std::unique_ptr<structure::ReducedModalModel> structure_;
    int shaker_index_ = -1;
};

}  // namespace sb::bench

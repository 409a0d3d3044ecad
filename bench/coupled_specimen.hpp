// The structure with what is attached to it (particle dampers, ...), stepped together: loose
// (staggered) coupling at the DEM time step, as in paper 000 section 3.1.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/attachment.hpp"
#include "bench/campaign_spec.hpp"
#include "bench/channels.hpp"
#include "bench/physics_spec.hpp"
#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/reduced_modal_model.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// The state a sweep carries from one point to the next (and through a checkpoint). Every
/// point starts at its own time 0 (phase 0 of its sine), so no structural clock is kept; a
/// DEM damper keeps its own clock (lock release) in its state.
struct SpecimenState {
    Eigen::VectorXd q;                         ///< modal displacements
    Eigen::VectorXd q_dot;                     ///< modal velocities
    std::vector<AttachmentState> attachments;  ///< per attachment
    /// Per attachment: the force [N] and moment [N m] it applied at its point in the last step.
    std::vector<Eigen::Matrix<double, 6, 1>> loads;
};

/// Structure + attachments + excitation. Every step: each attachment gets the motion of its
/// point and returns its load over the step; the loads at each point (the shaker's force
/// included) are summed and load the structure over the same step.
class CoupledSpecimen {
  public:
    /// `channels`: what is recorded after the reference (bench/channels.hpp); the first is
    /// the control channel. A damper-force channel reads the load of the attachment of the
    /// damper's name.
    CoupledSpecimen(const structure::LinearModel& model, const structure::ModalBasis& basis,
                    const structure::ExcitationSpec& excitation,
                    std::vector<Attachment> attachments, std::vector<RecordedChannel> channels,
                    double dt_max_s, int step_multiple = 1);
    /// The accelerations of `channel_points` along the excitation direction ("acc_<point>").
    CoupledSpecimen(const structure::LinearModel& model, const structure::ModalBasis& basis,
                    const structure::ExcitationSpec& excitation,
                    std::vector<Attachment> attachments,
                    const std::vector<std::string>& channel_points, double dt_max_s,
                    int step_multiple = 1);

    /// Drives the force excitation through an electrodynamic shaker (physics.shaker): the
    /// amplitude becomes the amplifier's voltage, which the reference channel "voltage"
    /// records, and a last channel "force" records the force into the structure. Its coil and
    /// suspension are the ShakerCoil among the attachments, its armature's mass the model's.
    /// Before set_frequency().
    void drive_through(const ShakerSpec& shaker);

    /// Drives a force excitation with `waveform(offset_s + t)` times the amplitude instead of
    /// sin(2 pi f t), t the point clock (which restore() sets back to 0, so a run that goes on
    /// across a restore passes its time so far as the offset): a random test's noise. An
    /// empty function goes back to the sine. Not for base excitation or a shaker (the config
    /// refuses them: bench/config_schema.cpp).
    void set_waveform(std::function<double(double)> waveform, double offset_s);

    /// Names of the recorded channels: the reference ("force", "voltage" or "base_acc")
    /// first, then each recorded channel, then "force" when a shaker drives.
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

    /// The particles the dampers' locks hold become rigid mass of the structure (its mass
    /// matrix, modes recomputed, its damping matrix kept: a modally damped structure's
    /// C = M Phi diag(2 zeta w) Phi^T M), their inertia left out of the dampers' loads; when a lock
    /// releases some, the structure changes to the model without them, keeping its physical
    /// displacement and velocity. Loose coupling applies a load one step late, so a held bed
    /// heavier than the modal mass at its point would otherwise be an explicit added mass the
    /// staggered loop cannot carry (it diverges). Before set_frequency().
    void carry_held_particles();

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

    /// State for warm starts and checkpoints; restore() continues every attachment from it
    /// (a DEM damper with its contact histories and clock) and restarts the point clock at 0.
    /// A sweep goes through state() and restore() between every two points, interrupted or
    /// not, so a resumed campaign repeats the same arithmetic.
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

    [[nodiscard]] const std::vector<Attachment>& attachments() const { return attachments_; }
    /// The motion of attachment i's point now.
    [[nodiscard]] PointMotion point_motion(std::size_t attachment) const;

  private:
    /// The model stepped now: the structure, with the held particles when carried.
    [[nodiscard]] const structure::LinearModel& active_model() const;
    [[nodiscard]] const structure::ModalBasis& active_basis() const;
    /// True when a lock freed particles the active model still carries (or the reverse).
    [[nodiscard]] bool held_changed() const;
    /// Builds the active model from the structure and every damper's held body.
    void build_held_model();
    /// Steps the structure of the active model from its state now; `project`: the state of
    /// the model stepped so far carried over in physical coordinates (x = Phi q, then
    /// q' = Phi'^T M' x).
    void rebuild_structure(bool project, double amplitude);
    /// Continues every attachment from `states` (taken relative to its point's pose before
    /// the structure jumped) with its point where the structure now puts it.
    void carry_attachments(const std::vector<AttachmentState>& states);
    /// The loads at the end of the next step: every attachment's (loads_) and the excitation
    /// at `time_s`, summed per point.
    void set_loads(double amplitude, double time_s);
    /// The drive at `time_s`: the reference channel's value (force, voltage or base
    /// acceleration).
    [[nodiscard]] double excitation_value(double amplitude, double time_s) const;
    /// The force the drive applies at the drive point (through a shaker: the blocked force of
    /// the voltage, ShakerCoil adding what the motion takes back).
    [[nodiscard]] double drive_force(double amplitude, double time_s) const;

    const structure::LinearModel* model_;
    const structure::ModalBasis* basis_;
    const structure::LinearModel* start_model_;
    const structure::ModalBasis* start_basis_;
    structure::ExcitationSpec excitation_;
    std::vector<Attachment> attachments_;
    std::vector<int> attachment_point_index_;
    std::vector<Eigen::Matrix<double, 6, 1>> loads_;       ///< last applied, per attachment
    std::vector<Eigen::Matrix<double, 6, 1>> next_loads_;  ///< work space of step()
    bool carry_held_ = false;  ///< the structure carries what the locks hold
    std::optional<structure::LinearModel> held_model_;  ///< set while particles are held
    std::optional<structure::ModalBasis> held_basis_;
    std::vector<int> held_counts_;  ///< per attachment: the locked particles held_model_ carries
    std::vector<HeldBody> held_bodies_;  ///< per attachment: what held_model_ carries
    std::vector<int> loaded_points_;     ///< every point a load acts at
    std::vector<Eigen::Matrix<double, 6, 1>> point_totals_;  ///< work space, per loaded point
    std::vector<RecordedChannel> channels_;
    /// Per channel: the structure's point index (motion, per frequency), or the attachment's
    /// index (force, from the constructor).
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
    std::optional<ShakerSpec> shaker_;
    std::complex<double> force_per_volt_ = 1.0;  ///< blocked force per volt at this frequency
    int coil_ = -1;                              ///< the ShakerCoil's attachment, if any
    std::function<double(double)> waveform_;     ///< set_waveform(); empty: the sine
    double waveform_offset_s_ = 0.0;
};

}  // namespace sb::bench

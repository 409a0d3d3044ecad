// Models attached at a point of the structure: the point's motion in, a load out, once per
// structural step; a state to carry from one point to the next and through checkpoints.
// A closed set dispatched once per step (std::variant, style.md): nothing virtual, and
// nothing at all inside the DEM loop. Adding a model (an impact oscillator, a describing
// function, air drag, a shaker) is one struct with these verbs and one variant alternative.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "bench/attachment_types.hpp"
#include "bench/describing_function.hpp"
#include "bench/iwan_joint.hpp"
#include "bench/shaker.hpp"
#include "dem/solver.hpp"
#include "dem/solver_state.hpp"

namespace sb::bench {

/// A particle damper simulated by DEM: its enclosure moves with the point (mounted with a
/// rotation and an offset), the particles are stepped, the wall force and moment load the
/// point (paper 000 section 3.1, loose coupling).
class DemDamper {
  public:
    /// `bed`: the settled particles in the enclosure frame; `rest_position_m`: the point's
    /// position at rest.
    DemDamper(const dem::SolverOptions& options, const Eigen::Matrix3d& mount_rotation,
              const Eigen::Vector3d& offset_m, const dem::ParticleSet& bed,
              const Eigen::Vector3d& rest_position_m);

    /// Moves the enclosure with the point, advances the particles by dt and returns their load
    /// on the point (the wall moment taken about the point).
    PointLoad step(const PointMotion& motion, double dt_s);
    /// The bed's weight at its centre of gravity, as a load on the point (for the static
    /// deflection a start adds).
    [[nodiscard]] PointLoad weight() const;
    /// The state to continue from exactly (the pose of the last step's start included).
    [[nodiscard]] AttachmentState state() const;
    /// The state relative to the enclosure's pose at `motion`: what rides with it when the
    /// structure jumps (restore_at()).
    [[nodiscard]] AttachmentState state_at(const PointMotion& motion);
    /// Continues exactly from `state` (its particles, contact springs, lock and clock).
    void restore(const AttachmentState& state);
    /// Continues from `state` with the enclosure moved rigidly to where `motion` puts it: the
    /// particles keep their enclosure-frame positions, relative velocities and contact
    /// springs (turned with the enclosure), the solver its clock.
    void restore_at(const AttachmentState& state, const PointMotion& motion);
    /// After restore(): the solver's energy ledger continues `saved`'s cumulative works
    /// (dem::Solver::continue_energy), as a run resumed from its checkpoint needs.
    void continue_energy(const dem::EnergyLedger& saved) { solver_->continue_energy(saved); }

    void set_frequency(double) {}

    /// The particles its lock holds now, as a rigid body at its point; mass 0 when none.
    [[nodiscard]] HeldBody held_body() const;
    /// From now on (restores included) the structure carries the held particles' inertia in
    /// its mass matrix, so the load leaves it out (dem::Solver::set_locked_inertia_external).
    void carry_held_inertia_in_structure();

    [[nodiscard]] const dem::Solver& solver() const { return *solver_; }
    [[nodiscard]] dem::EnclosureState enclosure(const PointMotion& motion) const;

  private:
    /// A solver continuing `state` with the enclosure at `at`, carrying what this damper
    /// carries (the held particles' inertia in the structure or not).
    void continue_from(const dem::SolverState& state, const dem::EnclosureState& at);

    std::unique_ptr<dem::Solver> solver_;
    dem::SolverOptions options_;
    Eigen::Matrix3d mount_rotation_;
    Eigen::Vector3d offset_m_;
    bool held_inertia_in_structure_ = false;
};

/// Particles as a rigid mass: part of the arrangement's structure already, it adds no load
/// and keeps no state.
struct RigidParticles {
    PointLoad step(const PointMotion&, double) { return {}; }
    [[nodiscard]] PointLoad weight() const { return {}; }
    [[nodiscard]] AttachmentState state() const { return {}; }
    [[nodiscard]] AttachmentState state_at(const PointMotion&) const { return {}; }
    void restore(const AttachmentState& s) { no_particles(s); }
    void restore_at(const AttachmentState& s, const PointMotion&) { no_particles(s); }
    void set_frequency(double) {}

  private:
    /// Particles in the state of a rigid mass belong to another model: never ignored.
    static void no_particles(const AttachmentState& s) {
        if (s.dem) {
            throw std::invalid_argument("rigid particles carry no state, this one holds particles");
        }
    }
};

/// A particle damper as its describing function (bench/describing_function.hpp): the complex
/// apparent mass M = M' + i M'' at the amplitude of its point's acceleration along the
/// excitation direction d over the last whole period. For a harmonic motion u(t) about its
/// mean u0, F1 = -M a1 is, in time, F = M' w^2 (u - u0) + w M'' v (a = -w^2 (u - u0), and
/// i a1 is a's quarter-period advance, -w v); it acts along d at the point, with the bed's
/// weight at its centre of gravity. The load is the one at the end of the step, as the coupled
/// specimen applies it. The stiffness form rather than -M' a from differenced
/// velocities: an explicit added mass near the point's own modal mass is unstable in a
/// staggered loop, a stiffness of M' w^2 (tens of N/m at the paper-000 tip) is not.
class DescribingFunctionDamper {
  public:
    /// `direction`: the excitation direction (normalised here); `rest_position_m`: the
    /// point at rest; `weight`: the bed's weight as a load on the point.
    DescribingFunctionDamper(std::shared_ptr<const DescribingFunction> function,
                             const Eigen::Vector3d& direction,
                             const Eigen::Vector3d& rest_position_m, const PointLoad& weight);

    /// The excitation frequency of the steps that follow [Hz].
    void set_frequency(double frequency_hz);
    PointLoad step(const PointMotion& motion, double dt_s);
    [[nodiscard]] PointLoad weight() const { return weight_; }
    [[nodiscard]] AttachmentState state() const;
    [[nodiscard]] AttachmentState state_at(const PointMotion&) const { return state(); }
    /// Continues from `state`; the amplitude is estimated again from the first step's motion
    /// (a period later from the whole period).
    void restore(const AttachmentState& state);
    void restore_at(const AttachmentState& state, const PointMotion&) { restore(state); }

    /// The describing function's value in use now.
    [[nodiscard]] const DescribingFunction::Value& value() const { return value_; }
    [[nodiscard]] double acceleration_m_s2() const { return state_.acceleration_m_s2; }

  private:
    void update_value();

    std::shared_ptr<const DescribingFunction> function_;
    Eigen::Vector3d direction_;
    Eigen::Vector3d rest_position_m_;
    PointLoad weight_;
    double frequency_hz_ = 0.0;
    DescribingState state_;
    DescribingFunction::Value value_;
    bool estimate_from_motion_ = true;  ///< the next step estimates the amplitude from its state
    // The current period's sums: steps, sum of u, sum of u e^{-i w t_k}.
    int steps_ = 0;
    double sum_u_ = 0.0;
    std::complex<double> sum_phasor_ = 0.0;
};

/// The verbs of an attachment that keeps no state between steps (the catalogue physics below):
/// no weight, an empty state, and a state that holds something refused, never ignored.
struct StatelessAttachment {
    [[nodiscard]] PointLoad weight() const { return {}; }
    [[nodiscard]] AttachmentState state() const { return {}; }
    [[nodiscard]] AttachmentState state_at(const PointMotion&) const { return {}; }
    void restore(const AttachmentState& s) const {
        if (s.dem || s.describing || s.sliders || s.coil_current_a) {
            throw std::invalid_argument("a stateless attachment was given a state");
        }
    }
    void restore_at(const AttachmentState& s, const PointMotion&) const { restore(s); }
    void set_frequency(double) {}
};

/// A strip of the beam under quadratic air drag, lumped at its midpoint (physics.air_drag;
/// bench/physics_attachments.hpp): F = -k |v_n| v_n n along the wide face's normal n, with
/// k = 1/2 rho C_D b l for a strip of width b and length l. Stateless; its load is that of the
/// motion at the step's start, applied over the step (the drag changes little in a step of
/// a few hundredths of a period at most).
class AirDragStrip : public StatelessAttachment {
  public:
    AirDragStrip(const Eigen::Vector3d& normal, double coefficient_kg_m);

    PointLoad step(const PointMotion& motion, double dt_s) const;

    /// Its describing function along n at the peak acceleration |a1| [m/s^2] and frequency
    /// [Hz]: for v = V sin(w t) the fundamental of -k |v| v is -(8 / 3 pi) k V v, so
    /// M = -i (8 / 3 pi) k |a1| / w^2, and |Q3| / |Q1| = 1/5 (|sin| sin = (8 / 3 pi) sin -
    /// (8 / 15 pi) sin 3 wt - ...), no even harmonic. Exact for a harmonic motion.
    [[nodiscard]] DescribingFunction::Value describing(double acceleration_m_s2,
                                                       double frequency_hz) const;

    [[nodiscard]] double coefficient_kg_m() const { return coefficient_kg_m_; }

  private:
    Eigen::Vector3d normal_;
    double coefficient_kg_m_;
};

/// Microslip in a joint as a power-law dashpot at its point (physics.microslip;
/// bench/physics_attachments.hpp): F = -c (|v_d| / v_ref)^chi v_d d along the excitation
/// direction d. Stateless, explicit as the air-drag strip.
class MicroslipDashpot : public StatelessAttachment {
  public:
    MicroslipDashpot(const Eigen::Vector3d& direction, double damping_n_s_per_m, double exponent,
                     double reference_velocity_m_s);

    PointLoad step(const PointMotion& motion, double dt_s) const;

    /// Its describing function along d at the peak acceleration |a1| [m/s^2] and frequency
    /// [Hz]: for v = V sin(w t), V = |a1| / w, the fundamental of |v|^chi v is
    /// kappa(chi) V^chi v with kappa = (2 / sqrt(pi)) Gamma((3 + chi) / 2) / Gamma((4 + chi) / 2)
    /// (1 at chi = 0, 8 / 3 pi at chi = 1), so M = -i c kappa (V / v_ref)^chi / w;
    /// |Q3| / |Q1| = chi / (4 + chi) from the same Fourier series, no even harmonic.
    [[nodiscard]] DescribingFunction::Value describing(double acceleration_m_s2,
                                                       double frequency_hz) const;

  private:
    Eigen::Vector3d direction_;
    double damping_n_s_per_m_;
    double exponent_;
    double reference_velocity_m_s_;
};

/// A hardening cubic spring from its point to the fixed frame (physics.cubic_spring;
/// bench/physics_attachments.hpp): F = -k3 u^3 d with u = d . (x - x_rest) at the step's end
/// (x + v dt). Stateless.
class CubicSpring : public StatelessAttachment {
  public:
    CubicSpring(const Eigen::Vector3d& direction, double stiffness_n_per_m3,
                const Eigen::Vector3d& rest_position_m);

    PointLoad step(const PointMotion& motion, double dt_s) const;

    /// Its describing function along d at the peak acceleration |a1| [m/s^2] and frequency
    /// [Hz]: for u = U sin(w t), U = |a1| / w^2, u^3 = (3/4) U^2 u - (1/4) U^3 sin 3wt, so the
    /// fundamental is a stiffness (3/4) k3 U^2 and M = -(3/4) k3 U^2 / w^2 (real: it moves
    /// the frequency, no damping); |Q3| / |Q1| = 1/3.
    [[nodiscard]] DescribingFunction::Value describing(double acceleration_m_s2,
                                                       double frequency_hz) const;

  private:
    Eigen::Vector3d direction_;
    double stiffness_n_per_m3_;
    Eigen::Vector3d rest_position_m_;
};

using AttachmentModel =
    std::variant<DemDamper, RigidParticles, DescribingFunctionDamper, AirDragStrip,
                 MicroslipDashpot, CubicSpring, IwanJoint, ShakerCoil>;

/// A model at a named point.
struct Attachment {
    std::string name;
    std::string point;
    AttachmentModel model;
};

PointLoad step(Attachment& attachment, const PointMotion& motion, double dt_s);
PointLoad weight(const Attachment& attachment);
AttachmentState state(const Attachment& attachment);
AttachmentState state_at(Attachment& attachment, const PointMotion& motion);
void restore(Attachment& attachment, const AttachmentState& state);
void restore_at(Attachment& attachment, const AttachmentState& state, const PointMotion& motion);
/// The excitation frequency of the steps that follow (a describing function needs it).
void set_frequency(Attachment& attachment, double frequency_hz);

/// The attachment's DEM solver, if it has one.
const dem::Solver* dem_solver(const Attachment& attachment);

/// A ParaView (legacy VTK) file of a DEM damper's bed in the enclosure frame, if it has one.
std::optional<std::string> bed_vtk_text(const Attachment& attachment);

}  // namespace sb::bench

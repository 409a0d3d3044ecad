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

#include "dem/solver.hpp"
#include "dem/solver_state.hpp"

namespace sb::bench {

/// Where a point of the structure is and how it moves (structure frame).
struct PointMotion {
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();    ///< rest position + displacement
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< of the point's small rotation
    Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
    Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
};

/// Force [N] and moment [N m] at a point, structure frame.
struct PointLoad {
    Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment_nm = Eigen::Vector3d::Zero();
};

/// What an attachment carries between points and through a checkpoint.
struct AttachmentState {
    std::optional<dem::SolverState> dem;  ///< a DEM damper's particles, histories and clock
};

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

    [[nodiscard]] const dem::Solver& solver() const { return *solver_; }
    [[nodiscard]] dem::EnclosureState enclosure(const PointMotion& motion) const;

  private:
    std::unique_ptr<dem::Solver> solver_;
    dem::SolverOptions options_;
    Eigen::Matrix3d mount_rotation_;
    Eigen::Vector3d offset_m_;
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

  private:
    /// Particles in the state of a rigid mass belong to another model: never ignored.
    static void no_particles(const AttachmentState& s) {
        if (s.dem) {
            throw std::invalid_argument("rigid particles carry no state, this one holds particles");
        }
    }
};

using AttachmentModel = std::variant<DemDamper, RigidParticles>;

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

/// The attachment's DEM solver, if it has one.
const dem::Solver* dem_solver(const Attachment& attachment);

/// A ParaView (legacy VTK) file of a DEM damper's bed in the enclosure frame, if it has one.
std::optional<std::string> bed_vtk_text(const Attachment& attachment);

}  // namespace sb::bench

// The electrodynamic shaker that drives a force-excited structure (physics.shaker;
// docs/diagnosis.md): an amplifier's voltage through the coil, the force factor Bl on the
// armature, the armature on its suspension, joined to the structure by a rigid stinger.
#pragma once

#include <Eigen/Core>
#include <complex>

#include "bench/attachment_types.hpp"
#include "bench/describing_function.hpp"
#include "bench/physics_spec.hpp"

namespace sb::bench {

/// The force per volt with the armature held still, G = Bl / (R + i w L): the blocked force
/// phasor per voltage phasor [N/V] at `frequency_hz`. The voltage V sin(w t) drives the
/// structure with the force |G| V sin(w t + arg G), less what the armature's motion takes
/// back (ShakerCoil).
std::complex<double> blocked_force_per_volt(const ShakerSpec& shaker, double frequency_hz);

/// What the shaker's moving parts add at the drive point, along the excitation direction d,
/// besides the armature's mass (part of the structural model): the suspension (k_s, c_s) and
/// the back-EMF. With the coil's equation L di/dt + R i = V - Bl v and the force Bl i, the
/// current splits (the equation is linear) into the voltage's share, whose force the specimen
/// applies as the drive (blocked_force_per_volt), and the motion's share i_v,
/// L di_v/dt + R i_v = -Bl v, whose force Bl i_v is an electrical dashpot of Bl^2 / R at low
/// frequency: the damping a voltage-referenced FRF shows and a force-referenced one does not
/// (research note on mismatch diagnosis, section 2; Varoto and de Oliveira 2002 on the force
/// drop-out at resonance). Its load is F = (Bl i_v - k_s u - c_s v) d, u = d . (x - x_rest).
class ShakerCoil {
  public:
    ShakerCoil(const Eigen::Vector3d& direction, const ShakerSpec& shaker,
               const Eigen::Vector3d& rest_position_m);

    /// Advances i_v over the step exactly for the velocity extrapolated from the step's start
    /// with the point's acceleration (the exponential of the coil's time constant L / R; with
    /// L = 0 the current follows the velocity at once) and returns the load at the step's end,
    /// the suspension stretched as far (the load the specimen applies at the step's end).
    PointLoad step(const PointMotion& motion, double dt_s);
    [[nodiscard]] PointLoad weight() const { return {}; }
    [[nodiscard]] AttachmentState state() const;
    [[nodiscard]] AttachmentState state_at(const PointMotion&) const { return state(); }
    /// Continues with the coil current of `state` (none: no current).
    void restore(const AttachmentState& state);
    void restore_at(const AttachmentState& state, const PointMotion&) { restore(state); }
    void set_frequency(double) {}

    /// Its describing function along d (linear: the same at every amplitude), Q1 = -M a1 with
    /// a = i w v = -w^2 u: M = -k_s / w^2 - i c_s / w - i Bl^2 / (w (R + i w L)).
    [[nodiscard]] DescribingFunction::Value describing(double acceleration_m_s2,
                                                       double frequency_hz) const;

    /// The motion's share of the coil current [A].
    [[nodiscard]] double current_a() const { return current_a_; }

  private:
    Eigen::Vector3d direction_;
    ShakerSpec shaker_;
    Eigen::Vector3d rest_position_m_;
    double current_a_ = 0.0;
};

}  // namespace sb::bench

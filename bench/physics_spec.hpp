// Physics a model may leave out, each an optional component of the structure or its rig that
// a diagnosis can switch on and fit (docs/diagnosis.md, the physics catalogue). Off by
// default: a config without [physics] simulates what it did before.
#pragma once

#include <string>

#include "core/violation.hpp"

namespace sb::bench {

/// Aerodynamic drag of a thin beam oscillating across its wide face: the Morison-type
/// quadratic force per unit length f = -1/2 rho C_D b |v| v along the face normal (research
/// note on mismatch diagnosis, section 2: zeta grows in proportion to the amplitude),
/// lumped at the midpoints of equal strips of the beam.
struct AirDragSpec {
    double drag_coefficient = 0.0;     ///< C_D of the section across its wide face; 0: off [-]
    double air_density_kg_m3 = 1.204;  ///< dry air at 20 degC and 1 atm
    int stations = 24;                 ///< strips the drag is lumped over

    [[nodiscard]] bool on() const { return drag_coefficient > 0.0; }
};

/// Microslip in a joint or clamp as a power-law dashpot at a point, along the excitation
/// direction: f = -c (|v| / v_ref)^chi v. Its equivalent damping grows like the amplitude to
/// the power chi (Iwan-type microslip gives 0 < chi < 1; research note on mismatch
/// diagnosis, section 2), without the stiffness loss a full Iwan element adds.
struct MicroslipSpec {
    std::string point;                    ///< named point of the joint
    double damping_n_s_per_m = 0.0;       ///< c at v = v_ref; 0: off [N s/m]
    double exponent = 0.5;                ///< chi [-]
    double reference_velocity_m_s = 0.1;  ///< v_ref [m/s]

    [[nodiscard]] bool on() const { return damping_n_s_per_m > 0.0; }
};

/// A hardening cubic spring at a point, along the excitation direction: f = -k3 u^3 with u the
/// point's displacement from rest. It stands in for the geometric stiffening of the driven
/// mode (the mode's frequency rises with the square of the amplitude, a clean third
/// harmonic; research note on mismatch diagnosis, section 2).
struct CubicSpringSpec {
    std::string point;                ///< named point
    double stiffness_n_per_m3 = 0.0;  ///< k3; 0: off [N/m^3]

    [[nodiscard]] bool on() const { return stiffness_n_per_m3 > 0.0; }
};

/// A joint's microslip and macroslip as a discrete Iwan element at a point, along the
/// excitation direction (bench/iwan_joint.hpp): the joint the linear model holds stuck, with
/// its stiffness K_T, loses stiffness and dissipates as its sliders move (Segalman's
/// four-parameter model with beta = 0: damping like the amplitude^(1 + chi) below macroslip,
/// with the slight softening a power-law dashpot lacks). Its slip force is
/// F_S = K_T phi_max (1 + chi) / (2 + chi).
struct IwanJointSpec {
    std::string point;                       ///< named point of the joint
    double stiffness_n_per_m = 0.0;          ///< K_T, the stuck joint's stiffness; 0: off [N/m]
    double macroslip_displacement_m = 1e-3;  ///< phi_max: the last slider moves beyond it [m]
    double exponent = -0.5;                  ///< chi of the slip density phi^chi [-]
    int elements = 96;                       ///< Jenkins elements the density is cut into

    [[nodiscard]] bool on() const { return stiffness_n_per_m > 0.0; }
};

/// The electrodynamic shaker between the amplifier and a force-excited structure's drive point
/// (bench/shaker.hpp): a coil of resistance R and inductance L in the field of a magnet (force
/// factor Bl), its armature of mass m_a on a suspension (k_s, c_s), joined to the structure by
/// a rigid stinger. On, the drive is the amplifier's voltage: the recording's reference
/// channel holds it, and a response channel `force` holds the force into the structure (a
/// force transducer at the stinger's end). Voltage- and force-referenced FRFs then differ as
/// they do on real rigs: the back-EMF damps the first, not the second.
struct ShakerSpec {
    double force_factor_n_per_a = 0.0;          ///< Bl; 0: off, the drive is an ideal force [N/A]
    double coil_resistance_ohm = 1.0;           ///< R, with the amplifier's output resistance [ohm]
    double coil_inductance_h = 0.0;             ///< L [H]
    double armature_mass_kg = 0.0;              ///< m_a: armature, table and stinger [kg]
    double suspension_stiffness_n_per_m = 0.0;  ///< k_s [N/m]
    double suspension_damping_n_s_per_m = 0.0;  ///< c_s [N s/m]

    [[nodiscard]] bool on() const { return force_factor_n_per_a > 0.0; }
};

struct PhysicsSpec {
    AirDragSpec air_drag;
    MicroslipSpec microslip;
    CubicSpringSpec cubic_spring;
    IwanJointSpec iwan_joint;
    ShakerSpec shaker;
};

}  // namespace sb::bench

// Physics a model may leave out, each an optional component of the structure or its rig that
// a diagnosis can switch on and fit (docs/diagnosis.md, the physics catalogue). Off by
// default: a config without [physics] simulates what it did before.
#pragma once

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

struct PhysicsSpec {
    AirDragSpec air_drag;
};

}  // namespace sb::bench

// Assembly of a beam spec into a LinearModel (elements, lumped masses, supports).
#pragma once

#include "structure/linear_model.hpp"

namespace sb::structure {

/// Finite element model of a straight beam along x: 6 DOFs per node, Timoshenko elements when
/// the shear modulus is given (Euler-Bernoulli otherwise, torsion then with G = E / (2 (1 +
/// 0.3))), rigid lumped masses, supports (clamped, pinned, free, elastic) with the fixed DOFs
/// eliminated. Points: every support and named point on the beam axis, and every named mass at
/// its centre of gravity (unless a named point has the same name).
LinearModel build_beam_model(const BeamSpec& beam, const ExcitationSpec& excitation);

/// Poisson's ratio assumed for torsion when no shear modulus is given [-].
inline constexpr double kDefaultPoissonRatio = 0.3;

}  // namespace sb::structure

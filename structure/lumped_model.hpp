// Chains and networks of point masses with springs and dashpots along the excitation direction.
#pragma once

#include "structure/linear_model.hpp"

namespace sb::structure {

/// One DOF per mass: its displacement [m] along the (normalised) excitation direction.
/// Points: one per mass, named after it. Springs and dashpots join two masses or a mass and
/// "ground". When any dashpot is non-zero the model carries the physical damping matrix C and
/// the damping spec's modal ratios are NOT used for it (integrators take C as is; the modal
/// model takes zeta_r = (phi_r^T C phi_r) / (2 omega_r), i.e. drops the modal coupling terms).
/// Base excitation ("ground" moves): r = K^-1 k_ground, the static response of the masses to
/// a unit ground displacement (the dashpot term C r u_b' is neglected).
LinearModel build_lumped_model(const LumpedSpec& lumped, const ExcitationSpec& excitation);

}  // namespace sb::structure

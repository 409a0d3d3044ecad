// Natural frequencies, mass-normalised mode shapes, modal damping and effective masses.
#pragma once

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "structure/linear_model.hpp"
#include "structure/spec.hpp"

namespace sb::structure {

struct Mode {
    double frequency_hz = 0.0;   ///< undamped natural frequency [Hz]
    double damping_ratio = 0.0;  ///< modal damping ratio [-]
    /// Generalised mass [kg] of the shape scaled so that its largest translation component
    /// over every sample location of the model (beam nodes, lumped-mass centres of gravity,
    /// lumped masses, named matrix DOFs) equals 1 m: with phi mass-normalised and
    /// u_max = max_j |T_j phi| over all translation rows T_j (x, y and z of every sample
    /// location, so the dominant direction is the component where the maximum occurs),
    /// modal_mass_kg = 1 / u_max^2. Infinite when the mode has no translation at all.
    double modal_mass_kg = 0.0;
    /// Effective modal mass [kg] for rigid translation along x, y, z: (phi^T M r_d)^2 with the
    /// rigid translation vector r_d. Summed over all modes it equals r_d^T M r_d, the mass not
    /// held by supports (Chopra, Dynamics of Structures, eq. 13.2.14). NaN when the model
    /// does not know its rigid translations (LinearModel::rigid_translation_known()).
    Eigen::Vector3d effective_mass_kg = Eigen::Vector3d::Zero();
};

struct ModalBasis {
    std::vector<Mode> modes;  ///< ascending frequency
    /// Free DOFs x modes, mass-normalised (phi^T M phi = 1); each shape's largest sample
    /// translation is positive (deterministic sign).
    Eigen::MatrixXd shapes;
};

/// The first `count` modes (fewer if the model has fewer DOFs), by the dense generalised
/// symmetric eigenproblem K phi = omega^2 M phi. Damping ratios from the spec, or from the
/// model's physical damping matrix when it has one: zeta_r = phi_r^T C phi_r / (2 omega_r).
ModalBasis compute_modes(const LinearModel& model, const DampingSpec& damping, int count);

/// 6 x modes: translation xyz and rotation xyz of every mode at a named point.
Eigen::Matrix<double, 6, Eigen::Dynamic> point_shapes(const LinearModel& model,
                                                      const ModalBasis& basis,
                                                      std::string_view point);

/// Circular natural frequencies [rad/s] of a basis.
Eigen::VectorXd circular_frequencies(const ModalBasis& basis);
/// Damping ratios [-] of a basis.
Eigen::VectorXd damping_ratios(const ModalBasis& basis);

}  // namespace sb::structure

// A structure imported as Matrix Market mass and stiffness matrices with named DOFs.
#pragma once

#include <filesystem>

#include "structure/linear_model.hpp"

namespace sb::structure {

/// Reads M and K (paths relative to base_dir unless absolute). Points: a named DOF "p.x" (or
/// .y, .z, .rx, .ry, .rz) makes point "p" with that row in its operator; a DOF name without a
/// component suffix makes a point moving along the excitation direction. Rigid translations:
/// from the rigid-body file when given, else from the named DOFs (known only when every row
/// is named). Masses added at named points (matrix.masses) join M through the point's
/// operator. Base excitation: relative coordinates with the influence vector r of the base
/// influence file, else the rigid translation along the excitation direction. Throws
/// MatrixMarketError on unreadable files, std::invalid_argument on matrices that do not fit
/// (size, symmetry, M not positive definite, rows outside, an influence vector of the wrong
/// size or none to be had).
LinearModel build_matrix_model(const MatrixSpec& matrix, const ExcitationSpec& excitation,
                               const std::filesystem::path& base_dir);

}  // namespace sb::structure

// A structure imported as Matrix Market mass and stiffness matrices with named DOFs.
#pragma once

#include <filesystem>

#include "structure/linear_model.hpp"

namespace sb::structure {

/// Reads M and K (paths relative to base_dir unless absolute). Points: a named DOF "p.x" (or
/// .y, .z, .rx, .ry, .rz) makes point "p" with that row in its operator; a DOF name without a
/// component suffix makes a point moving along the excitation direction. Rigid translations:
/// from the rigid-body file when given, else from the named DOFs (known only when every row
/// is named). Base excitation is not supported. Throws MatrixMarketError on unreadable files,
/// std::invalid_argument on matrices that do not fit (size, symmetry, M not positive
/// definite, rows outside).
LinearModel build_matrix_model(const MatrixSpec& matrix, const ExcitationSpec& excitation,
                               const std::filesystem::path& base_dir);

}  // namespace sb::structure

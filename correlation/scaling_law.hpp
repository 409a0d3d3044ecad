// How a mismatch scales with the excitation level: a residual Δ(A) between measurement and
// simulation, level by level, fitted by the shapes that name physics (research note on
// mismatch diagnosis, after Green and Worden 2015): constant (a viscous background), ∝ A
// (quadratic air drag, Mindlin microslip), ∝ 1/A (Coulomb slip, impacts), ∝ A² (cubic
// damping, geometric stiffening of the frequency), ∝ A^χ (Iwan-type microslip, 0 < χ < 1),
// or none at all. The shapes are compared by BIC (Schwarz 1978).
#pragma once

#include <string>
#include <vector>

namespace sb::correlation {

enum class ScalingShape { none, constant, linear, inverse, quadratic, power };

/// "none", "constant", "∝ A", "∝ 1/A", "∝ A²", "∝ A^χ".
std::string scaling_shape_name(ScalingShape shape);

/// One level's residual: Δ = measured − simulated, with its standard uncertainty.
struct LevelResidual {
    double level = 0.0;     ///< the excitation level A (> 0), in any unit [e.g. g]
    double residual = 0.0;  ///< Δ [feature's unit]
    double sigma = 0.0;     ///< of Δ (> 0) [feature's unit]
};

/// One shape fitted: Δ = c A^p.
struct ScalingFit {
    ScalingShape shape = ScalingShape::none;
    double coefficient = 0.0;  ///< c [feature's unit / A^p]
    double exponent = 0.0;     ///< p (fitted for power)
    /// Power: the exponent's 68 % interval (where χ² rises by 1 over its minimum) [-].
    double exponent_lo = 0.0;
    double exponent_hi = 0.0;
    double chi2 = 0.0;  ///< Σ ((Δ − c A^p)/σ)²
    int parameters = 0;
    double bic = 0.0;  ///< χ² + parameters ln n
};

/// Every shape fitted, the best (least BIC) first. The free exponent is searched within
/// [−3, 3]. Throws std::invalid_argument with no level, a level not > 0 or a σ not > 0.
std::vector<ScalingFit> fit_scaling(const std::vector<LevelResidual>& residuals);

/// "grows like A^0.52 (0.41 to 0.63)", "is constant", ... for a report.
std::string describe_scaling(const ScalingFit& fit);

}  // namespace sb::correlation

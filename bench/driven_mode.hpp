// The driven mode re-identified from a measured point: an equivalent linear mode that
// predicts how the drive must change from one frequency of a sweep to the next.
#pragma once

#include <complex>
#include <optional>
#include <string>

#include "structure/linear_model.hpp"
#include "structure/modal_analysis.hpp"
#include "structure/spec.hpp"

namespace sb::bench {

/// The accelerance at the control point for the shaker force, split as the driven mode r
/// plus the other modes' linear background B:
///   H(f) = -W^2 A / (w_r^2 - W^2 + 2 i c W) + B(f),   A = phi_control,r phi_shaker,r.
/// With particles the mode's frequency and damping change with the level; one measured
/// complex accelerance gives both back exactly (G = -W^2 A / (H - B) = w_r^2 - W^2 + 2 i c W),
/// the equivalent linear mode of that level, which then predicts H at the next frequency.
/// The 0.5 %-damped linear model alone predicts gain ratios near resonance several times too
/// large for a particle-damped beam.
class DrivenMode {
  public:
    /// `driven_mode_hz`: frequency of the mode the shaker drives (one of basis.modes).
    DrivenMode(const structure::LinearModel& model, const structure::ModalBasis& basis,
               const structure::ExcitationSpec& excitation, const std::string& control_point,
               double driven_mode_hz);

    /// Accelerance at `frequency_hz` of the equivalent mode matching `measured` (control
    /// acceleration / force fundamentals) at `measured_hz`; empty for base excitation or
    /// when the match is not a mode (negative stiffness or damping).
    [[nodiscard]] std::optional<std::complex<double>> predict(std::complex<double> measured,
                                                              double measured_hz,
                                                              double frequency_hz) const;

  private:
    [[nodiscard]] std::complex<double> background(double frequency_hz) const;

    const structure::LinearModel* model_;
    const structure::ModalBasis* basis_;
    std::string control_point_;
    std::string shaker_point_;
    Eigen::Vector3d direction_;
    bool force_ = false;
    int mode_ = 0;                 // index of the driven mode
    double modal_constant_ = 0.0;  // A [1/kg]
};

}  // namespace sb::bench

// The driven mode re-identified from a measured point.
#include "bench/driven_mode.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"
#include "structure/frf.hpp"

namespace sb::bench {

DrivenMode::DrivenMode(const structure::LinearModel& model, const structure::ModalBasis& basis,
                       const structure::ExcitationSpec& excitation,
                       const std::string& control_point, double driven_mode_hz)
    : model_(&model),
      basis_(&basis),
      control_point_(control_point),
      shaker_point_(excitation.point),
      direction_(excitation.direction.normalized()),
      force_(excitation.kind == structure::ExcitationSpec::Kind::force) {
    if (!force_) return;
    mode_ = -1;
    for (std::size_t r = 0; r < basis.modes.size(); ++r) {
        if (basis.modes[r].frequency_hz == driven_mode_hz) mode_ = static_cast<int>(r);
    }
    if (mode_ < 0) {
        throw std::invalid_argument("driven mode: no mode at " + format_value(driven_mode_hz) +
                                    " Hz");
    }
    // The mode's own term of the modal sum, at its natural frequency, gives A.
    const auto& m = basis.modes[static_cast<std::size_t>(mode_)];
    const double w = hz_to_rad_s(m.frequency_hz);
    const auto upto = [&](int modes) {
        return modes == 0
                   ? std::complex<double>(0.0)
                   : structure::modal_accelerance(model, basis, control_point_, direction_,
                                                  shaker_point_, direction_, m.frequency_hz, modes);
    };
    const std::complex<double> term = upto(mode_ + 1) - upto(mode_);
    modal_constant_ =
        (-term * std::complex<double>(0.0, 2.0 * m.damping_ratio * w * w) / (w * w)).real();
}

std::complex<double> DrivenMode::background(double frequency_hz) const {
    const auto upto = [&](int modes) {
        return modes == 0
                   ? std::complex<double>(0.0)
                   : structure::modal_accelerance(*model_, *basis_, control_point_, direction_,
                                                  shaker_point_, direction_, frequency_hz, modes);
    };
    const std::complex<double> all = upto(-1);
    return all - (upto(mode_ + 1) - upto(mode_));
}

std::optional<std::complex<double>> DrivenMode::predict(std::complex<double> measured,
                                                        double measured_hz,
                                                        double frequency_hz) const {
    if (!force_ || modal_constant_ == 0.0) return std::nullopt;
    const double wp = hz_to_rad_s(measured_hz);
    const std::complex<double> own = measured - background(measured_hz);
    if (std::abs(own) == 0.0) return std::nullopt;
    const std::complex<double> g = -wp * wp * modal_constant_ / own;
    const double wn2 = g.real() + wp * wp;   // w_r^2 of the equivalent mode
    const double c = g.imag() / (2.0 * wp);  // zeta_r w_r
    if (!(wn2 > 0.0 && c > 0.0)) return std::nullopt;
    const double w = hz_to_rad_s(frequency_hz);
    return -w * w * modal_constant_ / std::complex<double>(wn2 - w * w, 2.0 * c * w) +
           background(frequency_hz);
}

}  // namespace sb::bench

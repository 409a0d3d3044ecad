// Frequency response functions on a stepped-sine grid and the conversions between their forms.
#pragma once

#include <complex>
#include <vector>

namespace sb::identification {

/// What a transfer function divides by what. Complex amplitudes follow x(t) = Re{X e^{iωt}}
/// (peak amplitude), so d/dt is a multiplication by iω.
enum class FrfForm {
    receptance,   ///< displacement / force [m/N] (or relative displacement / base acceleration)
    mobility,     ///< velocity / force [m/(N s)]
    accelerance,  ///< acceleration / force [m/(N s^2)] (or transmissibility-like ratios)
};

/// A frequency response sampled on an increasing frequency grid.
struct Frf {
    std::vector<double> frequency_hz;         ///< strictly increasing [Hz]
    std::vector<std::complex<double>> value;  ///< one complex value per frequency
    FrfForm form = FrfForm::accelerance;      ///< what `value` divides by what
};

/// Throws std::invalid_argument unless sizes match, frequencies are > 0 and strictly increasing.
void check_frf(const Frf& frf);

/// Order k of a form as a multiple of receptance, (iω)^k × receptance: 0 receptance,
/// 1 mobility, 2 accelerance.
int form_order(FrfForm form);

/// The same FRF in another form: multiplies by (iω)^(k_to - k_from) with k = 0 (receptance),
/// 1 (mobility), 2 (accelerance); receptance = accelerance/(iω)^2, mobility = accelerance/(iω).
Frf convert(const Frf& frf, FrfForm to);

/// Transfer function C / reference per frequency (force excitation: accelerance when C is an
/// acceleration). Throws std::invalid_argument on size mismatch.
Frf transfer_function(const std::vector<double>& frequency_hz,
                      const std::vector<std::complex<double>>& response,
                      const std::vector<std::complex<double>>& reference, FrfForm form);

/// Absolute transmissibility response/table for base excitation [-], tagged
/// FrfForm::accelerance. For a base-excited SDOF it is 1 + ω²/(ωn² − ω² + 2iζωnω): the
/// accelerance shape of relative_transmissibility plus the constant 1, which in receptance is
/// the mass line −1/ω² that the estimators fit and subtract as residual (residual.hpp), so
/// they are exact on it too; with ResidualOptions::compensate false they are not.
Frf transmissibility(const std::vector<double>& frequency_hz,
                     const std::vector<std::complex<double>>& response_acceleration,
                     const std::vector<std::complex<double>>& table_acceleration);

/// Relative transmissibility (response - table)/table [-]. For a base-excited SDOF it equals
/// ω²/(ωn² − ω² + 2iζωnω), an accelerance of unit mass up to sign, so the estimators are exact
/// on it when it is tagged FrfForm::accelerance (which this function does).
Frf relative_transmissibility(const std::vector<double>& frequency_hz,
                              const std::vector<std::complex<double>>& response_acceleration,
                              const std::vector<std::complex<double>>& table_acceleration);

}  // namespace sb::identification

// FRF construction and form conversion (receptance, mobility, accelerance).
#include "identification/frf.hpp"

#include <cmath>
#include <stdexcept>

#include "core/units.hpp"

namespace sb::identification {

int form_order(FrfForm form) {
    switch (form) {
        case FrfForm::receptance:
            return 0;
        case FrfForm::mobility:
            return 1;
        case FrfForm::accelerance:
            return 2;
    }
    return 0;
}

void check_frf(const Frf& frf) {
    if (frf.frequency_hz.size() != frf.value.size()) {
        throw std::invalid_argument("FRF: frequency and value counts differ");
    }
    for (std::size_t i = 0; i < frf.frequency_hz.size(); ++i) {
        if (!(frf.frequency_hz[i] > 0.0) ||
            (i > 0 && !(frf.frequency_hz[i] > frf.frequency_hz[i - 1]))) {
            throw std::invalid_argument("FRF: frequencies must be > 0 and strictly increasing");
        }
    }
}

Frf convert(const Frf& frf, FrfForm to) {
    check_frf(frf);
    Frf out = frf;
    out.form = to;
    const int power = form_order(to) - form_order(frf.form);
    for (std::size_t i = 0; i < out.value.size(); ++i) {
        const std::complex<double> iw(0.0, hz_to_rad_s(frf.frequency_hz[i]));
        out.value[i] *= std::pow(iw, power);
    }
    return out;
}

Frf transfer_function(const std::vector<double>& frequency_hz,
                      const std::vector<std::complex<double>>& response,
                      const std::vector<std::complex<double>>& reference, FrfForm form) {
    if (response.size() != frequency_hz.size() || reference.size() != frequency_hz.size()) {
        throw std::invalid_argument("transfer_function: sizes differ");
    }
    Frf out{frequency_hz, {}, form};
    out.value.reserve(response.size());
    for (std::size_t i = 0; i < response.size(); ++i)
        out.value.push_back(response[i] / reference[i]);
    check_frf(out);
    return out;
}

Frf transmissibility(const std::vector<double>& frequency_hz,
                     const std::vector<std::complex<double>>& response_acceleration,
                     const std::vector<std::complex<double>>& table_acceleration) {
    return transfer_function(frequency_hz, response_acceleration, table_acceleration,
                             FrfForm::accelerance);
}

Frf relative_transmissibility(const std::vector<double>& frequency_hz,
                              const std::vector<std::complex<double>>& response_acceleration,
                              const std::vector<std::complex<double>>& table_acceleration) {
    Frf out = transmissibility(frequency_hz, response_acceleration, table_acceleration);
    for (auto& v : out.value) v -= 1.0;
    return out;
}

}  // namespace sb::identification

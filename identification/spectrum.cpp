// One-sided FFT of a real sequence with FFTW (a tested, fast FFT; FFTW3 is a project dependency).
#include "identification/spectrum.hpp"

#include <fftw3.h>

#include <mutex>
#include <stdexcept>
#include <string>

namespace sb::identification {
namespace {
// FFTW's planner is not thread-safe; execution with a fresh plan is (FFTW manual §5.4).
std::mutex planner_mutex;
}  // namespace

std::vector<std::complex<double>> real_spectrum(std::span<const double> x) {
    const int n = static_cast<int>(x.size());
    std::vector<double> in(x.begin(), x.end());
    std::vector<std::complex<double>> out(x.size() / 2 + 1);
    fftw_plan plan = nullptr;
    {
        std::lock_guard<std::mutex> lock(planner_mutex);
        // std::complex<double> is layout-compatible with fftw_complex (FFTW manual §4.1.1).
        plan = fftw_plan_dft_r2c_1d(n, in.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                    FFTW_ESTIMATE);
    }
    fftw_execute(plan);
    {
        std::lock_guard<std::mutex> lock(planner_mutex);
        fftw_destroy_plan(plan);
    }
    return out;
}

std::vector<double> inverse_real_spectrum(std::span<const std::complex<double>> spectrum, int n) {
    if (n < 1 || spectrum.size() != static_cast<std::size_t>(n / 2 + 1)) {
        throw std::invalid_argument("inverse_real_spectrum: " + std::to_string(spectrum.size()) +
                                    " bins do not make a sequence of " + std::to_string(n));
    }
    // c2r overwrites its input (FFTW manual §4.3.4): a copy.
    std::vector<std::complex<double>> in(spectrum.begin(), spectrum.end());
    std::vector<double> out(static_cast<std::size_t>(n));
    fftw_plan plan = nullptr;
    {
        std::lock_guard<std::mutex> lock(planner_mutex);
        plan = fftw_plan_dft_c2r_1d(n, reinterpret_cast<fftw_complex*>(in.data()), out.data(),
                                    FFTW_ESTIMATE);
    }
    fftw_execute(plan);
    {
        std::lock_guard<std::mutex> lock(planner_mutex);
        fftw_destroy_plan(plan);
    }
    for (double& v : out) v /= n;
    return out;
}

}  // namespace sb::identification

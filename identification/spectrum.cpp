// One-sided FFT of a real sequence with FFTW (a tested, fast FFT; FFTW3 is a project dependency).
#include "identification/spectrum.hpp"

#include <fftw3.h>

#include <mutex>

namespace sb::identification {

std::vector<std::complex<double>> real_spectrum(std::span<const double> x) {
    // FFTW's planner is not thread-safe; execution with a fresh plan is (FFTW manual §5.4).
    static std::mutex planner_mutex;
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

}  // namespace sb::identification

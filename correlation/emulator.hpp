// An emulator of a calibration's features over the free parameters: one Gaussian process per
// feature (Matérn 5/2, a length scale per parameter, a nugget for the DEM's seed scatter),
// trained on the evaluations so far, and the misfit it implies (Kennedy and O'Hagan 2001;
// Rasmussen and Williams 2006, ch. 2).
#pragma once

#include <memory>
#include <vector>

#include "correlation/evaluator.hpp"
#include "correlation/gaussian_process.hpp"

namespace sb::correlation {

class FeatureEmulator {
  public:
    /// Trains on the successful evaluations of `history` (their values mapped to the unit cube
    /// of `free`). Throws std::invalid_argument with fewer than 3 of them.
    FeatureEmulator(const Measurement& measurement, const std::vector<FreeParameter>& free,
                    const std::vector<Evaluation>& history);

    /// Mean and variance of every feature at unit-cube point `u`.
    void predict(const std::vector<double>& u, std::vector<double>& mean,
                 std::vector<double>& variance) const;
    /// ½ Σ r² of the emulated means against the measurement.
    [[nodiscard]] double misfit(const std::vector<double>& u) const;
    /// Residual of each feature of the emulated means, in standard deviations.
    [[nodiscard]] std::vector<double> residuals(const std::vector<double>& u) const;
    /// Expected improvement of the misfit below `best` at `u`, by averaging over fixed normal
    /// draws of the features (common random numbers: the same draws at every candidate, so
    /// candidates are compared without noise of their own).
    [[nodiscard]] double expected_improvement(const std::vector<double>& u, double best) const;
    [[nodiscard]] int trained_on() const { return trained_on_; }

  private:
    const Measurement* measurement_;
    std::vector<std::unique_ptr<GaussianProcess>> processes_;  ///< null: a constant feature
    std::vector<double> constant_;
    std::vector<double> simulated_sigma_;  ///< mean over evaluations of the simulation's scatter
    std::vector<std::vector<double>> draws_;
    int trained_on_ = 0;
    int fillings_ = 1;  ///< fillings each simulated value averages
};

/// The unit-cube point of least emulated misfit: a space-filling search over the cube and a
/// cloud around `near` (a search's best), then BOBYQA (COBYLA in one dimension) on the
/// emulator, which costs microseconds per call.
std::vector<double> least_emulated_misfit(const FeatureEmulator& emulator,
                                          const std::vector<FreeParameter>& free,
                                          const std::vector<double>& near);

}  // namespace sb::correlation

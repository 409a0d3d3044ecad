// Gaussian-process emulator of a scalar feature over a few (1–4) scaled parameters, for the
// calibration layer: it stands in for DEM simulations between the runs made, and its
// predictive distribution drives Bayesian optimisation by expected improvement.
//
// Written here rather than taken from a library: no C++ Gaussian-process library is packaged
// by Debian (limbo, the obvious candidate, is not), and a GP on Eigen is a few hundred lines:
// Rasmussen & Williams, Gaussian Processes for Machine Learning (2006), Algorithm 2.1 for the
// prediction and the log marginal likelihood, eq. 4.17 for the Matérn 5/2 covariance.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace sb::correlation {

/// Matérn 5/2 correlation of a scaled distance r >= 0 (R&W eq. 4.17 with ℓ = 1):
/// (1 + √5 r + 5/3 r²) exp(−√5 r). Twice differentiable sample paths: smooth enough for a
/// response surface, without the squared exponential's ill-conditioning. Throws
/// std::invalid_argument for a negative or NaN r.
double matern52(double r);

/// Hyperparameters of the covariance k(a, b) = signal_variance · matern52(r) with
/// r² = Σ_j ((a_j − b_j) / length_scales_j)², plus noise_variance on the diagonal.
struct GpHyperparameters {
    std::vector<double> length_scales;  ///< one per input dimension (ARD) [input units]
    double signal_variance = 1.0;       ///< of the standardised output [-]
    double noise_variance = 1e-6;       ///< nugget, of the standardised output [-]
};

/// Options of GaussianProcess::fit.
struct GpFitOptions {
    /// Lower bound of the fitted nugget [standardised output variance, -]; > 0 and below the
    /// upper bound kMaxNoiseVariance. Keeps the covariance matrix away from singular.
    double min_noise_variance = 1e-8;
    /// Fixed nugget [standardised output variance, -], >= 0; when unset the nugget is fitted.
    std::optional<double> noise_variance;
    /// Number of start points of the likelihood maximisation (>= 1): the first a central
    /// guess, the others a Halton sequence over a box of plausible values, so that a fit
    /// is reproducible.
    int restarts = 4;
};

/// Predictive distribution of the latent function f at a point: without the nugget.
struct GpPrediction {
    double mean = 0;      ///< [units of y]
    double variance = 0;  ///< [units of y²]
};

/// A Gaussian process with constant mean (the sample mean of y) and a Matérn 5/2 ARD
/// covariance, on outputs standardised by the sample mean and standard deviation.
class GaussianProcess {
  public:
    /// Bounds of the fitted hyperparameters (standardised output, inputs in the unit cube).
    static constexpr double kMinLengthScale = 1e-2;
    static constexpr double kMaxLengthScale = 1e2;
    static constexpr double kMinSignalVariance = 1e-4;
    static constexpr double kMaxSignalVariance = 1e4;
    /// Ten times the sample variance: data noisier than that would be all noise.
    static constexpr double kMaxNoiseVariance = 10.0;

    /// Fits the GP to x: n x d inputs (the caller scales them to the unit cube), y: n outputs.
    /// The hyperparameters maximise the log marginal likelihood (R&W eq. 2.30), found by NLopt's
    /// derivative-free LN_BOBYQA over log-parameters within the bounds above, from
    /// options.restarts fixed start points. Throws std::invalid_argument for n < 2, d < 1,
    /// mismatched sizes, non-finite values or invalid options; std::runtime_error if no
    /// jitter makes the covariance matrix positive definite.
    static GaussianProcess fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                               const GpFitOptions& options = {});

    /// Fits nothing: the GP with the given hyperparameters (standardised output) on x, y.
    /// Throws like fit, and for hyperparameters of the wrong size or not positive.
    static GaussianProcess with_hyperparameters(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                                const GpHyperparameters& hyperparameters);

    /// Predictive mean and variance of the latent f at x (d values) [units of y]
    /// (R&W Algorithm 2.1). Throws std::invalid_argument for a wrong size or non-finite x.
    GpPrediction predict(const Eigen::VectorXd& x) const;

    const GpHyperparameters& hyperparameters() const { return hyperparameters_; }
    /// Log marginal likelihood log p(y | x, θ) of the data in the units of y: that of the
    /// standardised outputs minus n log(sd of y) (the Jacobian of the standardisation).
    double log_marginal_likelihood() const { return log_marginal_likelihood_; }
    /// The nugget in the units of y².
    double noise_variance() const;
    /// Jitter added to the diagonal beyond the nugget because the covariance matrix was
    /// numerically singular (a pivot of its Cholesky factor at or below 1e-12 of the mean
    /// diagonal, e.g. repeated inputs with no nugget) [standardised output variance, -];
    /// 0 in the usual case.
    double jitter() const { return jitter_; }
    /// Sample mean and standard deviation (n − 1) by which y was standardised; the standard
    /// deviation is 1 when every y is equal.
    double output_mean() const { return output_mean_; }
    double output_scale() const { return output_scale_; }
    int dimension() const { return static_cast<int>(x_.cols()); }
    int sample_count() const { return static_cast<int>(x_.rows()); }

  private:
    GaussianProcess() = default;

    Eigen::MatrixXd x_;
    GpHyperparameters hyperparameters_;
    double output_mean_ = 0.0;
    double output_scale_ = 1.0;
    double jitter_ = 0.0;
    double log_marginal_likelihood_ = 0.0;
    Eigen::LLT<Eigen::MatrixXd> cholesky_;  ///< of K + (nugget + jitter) I, standardised
    Eigen::VectorXd alpha_;                 ///< (K + σn² I)⁻¹ ỹ (R&W Algorithm 2.1, line 3)
};

/// Expected improvement below `best` (minimisation) of a normal N(mean, sd²):
/// E[max(best − Y, 0)] = (best − mean) Φ(z) + sd φ(z), z = (best − mean) / sd
/// (Jones, Schonlau & Welch 1998, Efficient global optimization); max(best − mean, 0) when sd = 0.
/// Throws std::invalid_argument for a negative or non-finite sd, or non-finite best or mean.
double expected_improvement(double best, double mean, double sd);

}  // namespace sb::correlation

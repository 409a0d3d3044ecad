#include "correlation/gaussian_process.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sb::correlation {

namespace {

const double kSqrt5 = std::sqrt(5.0);

/// Matérn 5/2 without the argument check, for the covariance loops. With s = √5 r,
/// 5/3 r² = s²/3.
double matern52_unchecked(double r) {
    const double s = kSqrt5 * r;
    return (1.0 + s + s * s / 3.0) * std::exp(-s);
}

/// A pivot of the Cholesky factor at or below this fraction of the mean diagonal counts as
/// singular: the solves would carry errors of the order of 1 / pivot · eps. Far below any
/// sensible nugget (the default lower bound is 1e-8), so it acts only on singular matrices.
constexpr double kMinRelativePivot = 1e-12;
/// Jitter ladder: 10^-10, 10^-9, ..., 10^-4 of the mean diagonal. Beyond 1e-4 the jitter would
/// change the model rather than its numerics.
constexpr int kFirstJitterExponent = -10;
constexpr int kLastJitterExponent = -4;

void check_data(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
    if (x.rows() < 2) {
        throw std::invalid_argument("GaussianProcess: needs at least 2 samples, got " +
                                    std::to_string(x.rows()));
    }
    if (x.cols() < 1) {
        throw std::invalid_argument("GaussianProcess: inputs need at least 1 dimension");
    }
    if (y.size() != x.rows()) {
        throw std::invalid_argument("GaussianProcess: " + std::to_string(x.rows()) +
                                    " input rows but " + std::to_string(y.size()) + " outputs");
    }
    if (!x.allFinite()) throw std::invalid_argument("GaussianProcess: non-finite input");
    if (!y.allFinite()) throw std::invalid_argument("GaussianProcess: non-finite output");
}

void check_hyperparameters(const GpHyperparameters& h, Eigen::Index dimension) {
    if (static_cast<Eigen::Index>(h.length_scales.size()) != dimension) {
        throw std::invalid_argument("GaussianProcess: " + std::to_string(dimension) +
                                    " dimensions but " + std::to_string(h.length_scales.size()) +
                                    " length scales");
    }
    for (const double l : h.length_scales) {
        if (!(l > 0.0) || !std::isfinite(l)) {
            throw std::invalid_argument("GaussianProcess: length scales must be > 0 and finite");
        }
    }
    if (!(h.signal_variance > 0.0) || !std::isfinite(h.signal_variance)) {
        throw std::invalid_argument("GaussianProcess: signal variance must be > 0 and finite");
    }
    if (!(h.noise_variance >= 0.0) || !std::isfinite(h.noise_variance)) {
        throw std::invalid_argument("GaussianProcess: noise variance must be >= 0 and finite");
    }
}

void check_options(const GpFitOptions& options) {
    if (!(options.min_noise_variance > 0.0) ||
        !(options.min_noise_variance < GaussianProcess::kMaxNoiseVariance)) {
        throw std::invalid_argument("GaussianProcess: min_noise_variance must be in (0, " +
                                    std::to_string(GaussianProcess::kMaxNoiseVariance) + ")");
    }
    if (options.noise_variance &&
        (!(*options.noise_variance >= 0.0) || !std::isfinite(*options.noise_variance))) {
        throw std::invalid_argument(
            "GaussianProcess: fixed noise_variance must be >= 0 and finite");
    }
    if (options.restarts < 1) {
        throw std::invalid_argument("GaussianProcess: restarts must be >= 1");
    }
}

/// Squared differences of the inputs, one n x n matrix per dimension, computed once per fit:
/// the likelihood is evaluated hundreds of times with only the length scales changing.
std::vector<Eigen::MatrixXd> squared_differences(const Eigen::MatrixXd& x) {
    const Eigen::Index n = x.rows();
    std::vector<Eigen::MatrixXd> d2;
    d2.reserve(static_cast<std::size_t>(x.cols()));
    for (Eigen::Index k = 0; k < x.cols(); ++k) {
        Eigen::MatrixXd m(n, n);
        for (Eigen::Index j = 0; j < n; ++j) {
            for (Eigen::Index i = 0; i < n; ++i) {
                const double dx = x(i, k) - x(j, k);
                m(i, j) = dx * dx;
            }
        }
        d2.push_back(std::move(m));
    }
    return d2;
}

/// K + σn² I of the training inputs (standardised output). The kernel (a square root and an
/// exponential per entry, the likelihood's largest cost after the Cholesky factor) is
/// evaluated on the lower triangle and mirrored: the matrix is symmetric.
Eigen::MatrixXd covariance_matrix(const std::vector<Eigen::MatrixXd>& d2,
                                  const GpHyperparameters& h) {
    const Eigen::Index n = d2.front().rows();
    std::vector<double> length_squared(d2.size());
    for (std::size_t a = 0; a < d2.size(); ++a) {
        length_squared[a] = h.length_scales[a] * h.length_scales[a];
    }
    Eigen::MatrixXd k(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = j; i < n; ++i) {
            double r2 = 0.0;  // Σ_k d2_k / l_k², in the order of k
            for (std::size_t a = 0; a < d2.size(); ++a) r2 += d2[a](i, j) / length_squared[a];
            k(i, j) = h.signal_variance * matern52_unchecked(std::sqrt(r2));
            k(j, i) = k(i, j);
        }
    }
    k.diagonal().array() += h.noise_variance;
    return k;
}

struct Factorisation {
    Eigen::LLT<Eigen::MatrixXd> llt;
    double jitter = 0.0;
    bool ok = false;
};

bool acceptable(const Eigen::LLT<Eigen::MatrixXd>& llt, double mean_diagonal) {
    if (llt.info() != Eigen::Success) return false;
    const Eigen::VectorXd pivots = llt.matrixLLT().diagonal().array().square();
    return pivots.allFinite() && pivots.minCoeff() > kMinRelativePivot * mean_diagonal;
}

/// Cholesky factor of k, with jitter on the diagonal if k is numerically singular: repeated
/// or nearly repeated inputs with a nugget too small to separate them leave K + σn² I
/// positive semi-definite at best, and rounding can make it indefinite. The smallest jitter
/// of the ladder that gives acceptable pivots is kept and reported (GaussianProcess::jitter).
Factorisation factorise(Eigen::MatrixXd k) {
    Factorisation f;
    const double mean_diagonal = k.diagonal().mean();
    if (!(mean_diagonal > 0.0) || !std::isfinite(mean_diagonal)) return f;
    f.llt.compute(k);
    if (acceptable(f.llt, mean_diagonal)) {
        f.ok = true;
        return f;
    }
    double added = 0.0;
    for (int exponent = kFirstJitterExponent; exponent <= kLastJitterExponent; ++exponent) {
        const double jitter = std::pow(10.0, exponent) * mean_diagonal;
        k.diagonal().array() += jitter - added;
        added = jitter;
        f.llt.compute(k);
        if (acceptable(f.llt, mean_diagonal)) {
            f.jitter = jitter;
            f.ok = true;
            return f;
        }
    }
    return f;
}

/// log p(ỹ | x, θ) = −½ ỹᵀα − Σ log L_ii − n/2 log 2π (R&W Algorithm 2.1, line 7).
double standardised_log_likelihood(const Factorisation& f, const Eigen::VectorXd& y,
                                   Eigen::VectorXd& alpha) {
    alpha = f.llt.solve(y);
    const double log_det_half = f.llt.matrixLLT().diagonal().array().log().sum();
    const double n = static_cast<double>(y.size());
    return -0.5 * y.dot(alpha) - log_det_half - 0.5 * n * std::log(2.0 * std::numbers::pi);
}

/// The likelihood maximisation over p = (log ℓ_1..d, log σf², [log σn²]).
struct Problem {
    const std::vector<Eigen::MatrixXd>* d2 = nullptr;
    const Eigen::VectorXd* y = nullptr;
    std::optional<double> fixed_noise;
    std::size_t dimension = 0;
    double best_value = std::numeric_limits<double>::infinity();
    std::vector<double> best_parameters;

    GpHyperparameters hyperparameters(const double* p) const {
        GpHyperparameters h;
        h.length_scales.resize(dimension);
        for (std::size_t k = 0; k < dimension; ++k) h.length_scales[k] = std::exp(p[k]);
        h.signal_variance = std::exp(p[dimension]);
        h.noise_variance = fixed_noise ? *fixed_noise : std::exp(p[dimension + 1]);
        return h;
    }
};

/// Returned where the covariance cannot be factorised even with the largest jitter: a large
/// finite value, because BOBYQA's quadratic models do not survive infinities.
constexpr double kPenalty = 1e100;

double negative_log_likelihood(unsigned count, const double* p, double* /*gradient*/, void* data) {
    auto& problem = *static_cast<Problem*>(data);
    try {
        const Factorisation f =
            factorise(covariance_matrix(*problem.d2, problem.hyperparameters(p)));
        if (!f.ok) return kPenalty;
        Eigen::VectorXd alpha;
        const double value = -standardised_log_likelihood(f, *problem.y, alpha);
        if (!std::isfinite(value)) return kPenalty;
        if (value < problem.best_value) {
            problem.best_value = value;
            problem.best_parameters.assign(p, p + count);
        }
        return value;
    } catch (...) {
        // No exception may cross NLopt's C frames.
        return kPenalty;
    }
}

/// Radical inverse of index in a prime base: the Halton sequence's coordinate.
double radical_inverse(unsigned index, unsigned base) {
    double result = 0.0;
    double fraction = 1.0 / base;
    while (index > 0) {
        result += fraction * (index % base);
        index /= base;
        fraction /= base;
    }
    return result;
}

std::vector<unsigned> first_primes(std::size_t count) {
    std::vector<unsigned> primes;
    for (unsigned candidate = 2; primes.size() < count; ++candidate) {
        if (std::none_of(primes.begin(), primes.end(),
                         [&](unsigned q) { return candidate % q == 0; })) {
            primes.push_back(candidate);
        }
    }
    return primes;
}

/// y by its sample mean and standard deviation (n − 1).
struct Standardisation {
    double mean = 0.0;
    double scale = 1.0;
    Eigen::VectorXd y;
};

Standardisation standardise(const Eigen::VectorXd& y) {
    Standardisation s;
    s.mean = y.mean();
    const double variance = (y.array() - s.mean).square().sum() / static_cast<double>(y.size() - 1);
    // Equal outputs: nothing to scale; the GP is then the constant mean.
    s.scale = variance > 0.0 ? std::sqrt(variance) : 1.0;
    s.y = (y.array() - s.mean) / s.scale;
    return s;
}

using OptimiserHandle = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, void (*)(nlopt_opt)>;

}  // namespace

double matern52(double r) {
    if (!(r >= 0.0)) throw std::invalid_argument("matern52: r must be >= 0");
    return matern52_unchecked(r);
}

GaussianProcess GaussianProcess::with_hyperparameters(const Eigen::MatrixXd& x,
                                                      const Eigen::VectorXd& y,
                                                      const GpHyperparameters& hyperparameters) {
    check_data(x, y);
    check_hyperparameters(hyperparameters, x.cols());
    GaussianProcess gp;
    gp.x_ = x;
    gp.hyperparameters_ = hyperparameters;
    const Standardisation s = standardise(y);
    gp.output_mean_ = s.mean;
    gp.output_scale_ = s.scale;
    const Eigen::VectorXd& standardised = s.y;

    Factorisation f = factorise(covariance_matrix(squared_differences(x), hyperparameters));
    if (!f.ok) {
        const std::string largest = "1e" + std::to_string(kLastJitterExponent);
        throw std::runtime_error(
            "GaussianProcess: covariance matrix not positive definite even "
            "with a jitter of " +
            largest + " of its mean diagonal");
    }
    gp.log_marginal_likelihood_ = standardised_log_likelihood(f, standardised, gp.alpha_) -
                                  static_cast<double>(y.size()) * std::log(gp.output_scale_);
    gp.jitter_ = f.jitter;
    gp.cholesky_ = std::move(f.llt);
    return gp;
}

GaussianProcess GaussianProcess::fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                     const GpFitOptions& options) {
    check_data(x, y);
    check_options(options);

    const Eigen::VectorXd standardised = standardise(y).y;
    const std::vector<Eigen::MatrixXd> d2 = squared_differences(x);

    Problem problem;
    problem.d2 = &d2;
    problem.y = &standardised;
    problem.fixed_noise = options.noise_variance;
    problem.dimension = static_cast<std::size_t>(x.cols());
    const std::size_t d = problem.dimension;
    const std::size_t count = d + (options.noise_variance ? 1 : 2);

    std::vector<double> lower(count), upper(count);
    // Box of the start points (log), inside the bounds: length scales from a twentieth of the
    // cube to twice its side, signal variances around the standardised variance of 1, nuggets
    // from tiny to a third of the output variance.
    std::vector<double> start_lower(count), start_upper(count), centre(count);
    for (std::size_t k = 0; k < d; ++k) {
        lower[k] = std::log(kMinLengthScale);
        upper[k] = std::log(kMaxLengthScale);
        start_lower[k] = std::log(0.05);
        start_upper[k] = std::log(2.0);
        centre[k] = std::log(0.3);
    }
    lower[d] = std::log(kMinSignalVariance);
    upper[d] = std::log(kMaxSignalVariance);
    start_lower[d] = std::log(0.2);
    start_upper[d] = std::log(5.0);
    centre[d] = 0.0;
    if (!options.noise_variance) {
        lower[d + 1] = std::log(options.min_noise_variance);
        upper[d + 1] = std::log(kMaxNoiseVariance);
        start_lower[d + 1] = std::log(std::max(options.min_noise_variance, 1e-6));
        start_upper[d + 1] = std::max(std::log(0.3), start_lower[d + 1]);
        centre[d + 1] = std::clamp(std::log(1e-3), start_lower[d + 1], start_upper[d + 1]);
    }

    // Half an e-fold, or less where a bound box is narrow (BOBYQA's first trust region must
    // fit inside the bounds).
    double initial_step = 0.5;
    for (std::size_t k = 0; k < count; ++k) {
        initial_step = std::min(initial_step, 0.25 * (upper[k] - lower[k]));
    }
    const std::vector<unsigned> primes = first_primes(count);
    for (int start = 0; start < options.restarts; ++start) {
        std::vector<double> p = centre;
        if (start > 0) {
            for (std::size_t k = 0; k < count; ++k) {
                const double u = radical_inverse(static_cast<unsigned>(start), primes[k]);
                p[k] = start_lower[k] + u * (start_upper[k] - start_lower[k]);
            }
        }
        OptimiserHandle opt(nlopt_create(NLOPT_LN_BOBYQA, static_cast<unsigned>(count)),
                            nlopt_destroy);
        if (!opt) throw std::runtime_error("GaussianProcess: nlopt_create failed");
        nlopt_set_lower_bounds(opt.get(), lower.data());
        nlopt_set_upper_bounds(opt.get(), upper.data());
        nlopt_set_min_objective(opt.get(), negative_log_likelihood, &problem);
        // Log-parameters: an absolute tolerance is a relative one on the parameters.
        nlopt_set_xtol_abs1(opt.get(), 1e-7);
        nlopt_set_ftol_abs(opt.get(), 1e-10);
        nlopt_set_maxeval(opt.get(), static_cast<int>(500 + 300 * count));
        nlopt_set_initial_step1(opt.get(), initial_step);
        double value = 0.0;
        // Whatever the return code (a roundoff or evaluation limit is no failure of the model),
        // the best point evaluated is kept in the problem.
        nlopt_optimize(opt.get(), p.data(), &value);
    }
    if (problem.best_parameters.empty()) {
        throw std::runtime_error(
            "GaussianProcess: the likelihood could not be evaluated at any hyperparameters");
    }
    return with_hyperparameters(x, y, problem.hyperparameters(problem.best_parameters.data()));
}

GpPrediction GaussianProcess::predict(const Eigen::VectorXd& x) const {
    if (x.size() != x_.cols()) {
        throw std::invalid_argument("GaussianProcess::predict: " + std::to_string(x.size()) +
                                    " values for " + std::to_string(x_.cols()) + " dimensions");
    }
    if (!x.allFinite()) throw std::invalid_argument("GaussianProcess::predict: non-finite input");
    const Eigen::Index n = x_.rows();
    const double sf2 = hyperparameters_.signal_variance;
    Eigen::VectorXd k_star(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        double r2 = 0.0;
        for (Eigen::Index k = 0; k < x_.cols(); ++k) {
            const double dx = (x(k) - x_(i, k)) / hyperparameters_.length_scales[k];
            r2 += dx * dx;
        }
        k_star(i) = sf2 * matern52_unchecked(std::sqrt(r2));
    }
    // R&W Algorithm 2.1, lines 4-6: f̄* = k*ᵀα, v = L \ k*, V[f*] = k(x*, x*) − vᵀv.
    const double mean = k_star.dot(alpha_);
    const Eigen::VectorXd v = cholesky_.matrixL().solve(k_star);
    // Rounding can make the difference slightly negative at a training point.
    const double variance = std::max(sf2 - v.squaredNorm(), 0.0);
    return {output_mean_ + output_scale_ * mean, output_scale_ * output_scale_ * variance};
}

double GaussianProcess::noise_variance() const {
    return hyperparameters_.noise_variance * output_scale_ * output_scale_;
}

double expected_improvement(double best, double mean, double sd) {
    if (!std::isfinite(best) || !std::isfinite(mean)) {
        throw std::invalid_argument("expected_improvement: best and mean must be finite");
    }
    if (!(sd >= 0.0) || !std::isfinite(sd)) {
        throw std::invalid_argument("expected_improvement: sd must be >= 0 and finite");
    }
    const double gain = best - mean;
    if (sd == 0.0) return std::max(gain, 0.0);
    const double z = gain / sd;
    const double cdf = 0.5 * std::erfc(-z / std::numbers::sqrt2);
    const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
    // Far below best (z << 0) the two terms cancel; the exact value is never negative.
    return std::max(gain * cdf + sd * pdf, 0.0);
}

}  // namespace sb::correlation

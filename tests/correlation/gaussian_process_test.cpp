// The Gaussian-process emulator: the Matérn 5/2 correlation, interpolation, noise and ARD
// length scales, the likelihood and prediction against a direct computation, and expected
// improvement against a numerical integral.
#include "correlation/gaussian_process.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace sb::correlation {
namespace {

constexpr double kPi = std::numbers::pi;

double smooth(double x) { return std::sin(2.0 * kPi * x) + x; }

/// Matérn covariance of general order ν (R&W eq. 4.14, ℓ = 1):
/// 2^(1−ν) / Γ(ν) (√(2ν) r)^ν K_ν(√(2ν) r), with its limit 1 at r = 0.
double general_matern(double nu, double r) {
    if (r == 0.0) return 1.0;
    const double s = std::sqrt(2.0 * nu) * r;
    return std::pow(2.0, 1.0 - nu) / std::tgamma(nu) * std::pow(s, nu) * std::cyl_bessel_k(nu, s);
}

/// Halton point index i (from 1) in bases 2 and 3: a deterministic scatter over the unit square.
double halton(unsigned i, unsigned base) {
    double result = 0.0;
    double f = 1.0 / base;
    for (; i > 0; i /= base, f /= base) result += f * (i % base);
    return result;
}

Eigen::MatrixXd halton_square(int n) {
    Eigen::MatrixXd x(n, 2);
    for (int i = 0; i < n; ++i) {
        x(i, 0) = halton(static_cast<unsigned>(i + 1), 2);
        x(i, 1) = halton(static_cast<unsigned>(i + 1), 3);
    }
    return x;
}

double sample_mean(const Eigen::VectorXd& y) { return y.sum() / static_cast<double>(y.size()); }

double sample_variance(const Eigen::VectorXd& y) {
    const double m = sample_mean(y);
    double s = 0.0;
    for (Eigen::Index i = 0; i < y.size(); ++i) s += (y(i) - m) * (y(i) - m);
    return s / static_cast<double>(y.size() - 1);
}

/// The covariance written out from its definition: σf² (1 + √5 r + 5r²/3) exp(−√5 r),
/// r² = Σ ((a_j − b_j) / ℓ_j)² (R&W eq. 4.17 with ARD distances).
double covariance(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const GpHyperparameters& h) {
    double r2 = 0.0;
    for (Eigen::Index j = 0; j < a.size(); ++j) {
        r2 += std::pow((a(j) - b(j)) / h.length_scales[static_cast<std::size_t>(j)], 2);
    }
    const double r = std::sqrt(r2);
    return h.signal_variance * (1.0 + std::sqrt(5.0) * r + 5.0 * r2 / 3.0) *
           std::exp(-std::sqrt(5.0) * r);
}

Eigen::MatrixXd training_covariance(const Eigen::MatrixXd& x, const GpHyperparameters& h) {
    const Eigen::Index n = x.rows();
    Eigen::MatrixXd k(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < n; ++j) {
            k(i, j) = covariance(x.row(i).transpose(), x.row(j).transpose(), h);
        }
        k(i, i) += h.noise_variance;
    }
    return k;
}

/// log N(ỹ; 0, K + σn² I) of the standardised outputs, by LDLT (log det = Σ log D_i) and an
/// LU solve: not the Cholesky of the code under test.
double direct_standardised_log_likelihood(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                          const GpHyperparameters& h) {
    const double m = sample_mean(y);
    const double s = std::sqrt(sample_variance(y));
    const Eigen::VectorXd ys = (y.array() - m) / s;
    const Eigen::MatrixXd k = training_covariance(x, h);
    const double log_det = k.ldlt().vectorD().array().log().sum();
    const double quad = ys.dot(k.fullPivLu().solve(ys));
    return -0.5 * quad - 0.5 * log_det - 0.5 * static_cast<double>(y.size()) * std::log(2.0 * kPi);
}

struct Noisy {
    Eigen::MatrixXd x;
    Eigen::VectorXd y;
    Eigen::VectorXd truth;
};

/// 60 equispaced points of smooth(x) plus N(0, σ²) noise from a fixed seed.
Noisy noisy_smooth(double sigma) {
    const int n = 60;
    Noisy d{Eigen::MatrixXd(n, 1), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    std::mt19937 generator(20240607u);
    std::normal_distribution<double> noise(0.0, sigma);
    for (int i = 0; i < n; ++i) {
        d.x(i, 0) = i / double(n - 1);
        d.truth(i) = smooth(d.x(i, 0));
        d.y(i) = d.truth(i) + noise(generator);
    }
    return d;
}

/// A 2-D surface plus noise on 25 Halton points: both inputs matter, with different
/// length scales.
Noisy noisy_surface() {
    const int n = 25;
    Noisy d{halton_square(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    std::mt19937 generator(7u);
    std::normal_distribution<double> noise(0.0, 0.05);
    for (int i = 0; i < n; ++i) {
        d.truth(i) = std::sin(3.0 * d.x(i, 0)) + 0.5 * std::cos(5.0 * d.x(i, 1));
        d.y(i) = d.truth(i) + noise(generator);
    }
    return d;
}

Eigen::VectorXd point(std::initializer_list<double> values) {
    Eigen::VectorXd p(static_cast<Eigen::Index>(values.size()));
    Eigen::Index i = 0;
    for (const double v : values) p(i++) = v;
    return p;
}

TEST(Matern52, IsOneAtZero) { EXPECT_EQ(matern52(0.0), 1.0); }

TEST(Matern52, EqualsTheGeneralMaternOfOrderFiveHalves) {
    for (const double r : {1e-3, 0.1, 0.5, 1.0, 2.5, 6.0}) {
        EXPECT_NEAR(matern52(r), general_matern(2.5, r), 1e-12) << "r = " << r;
    }
}

TEST(Matern52, EqualsTheClosedFormOfRasmussenWilliams) {
    // (1 + √5 r + 5r²/3) e^(−√5 r) at r = 1 and r = 2, evaluated by hand with √5 = 2.2360679...
    const double s5 = std::sqrt(5.0);
    EXPECT_NEAR(matern52(1.0), (1.0 + s5 + 5.0 / 3.0) * std::exp(-s5), 1e-15);
    EXPECT_NEAR(matern52(2.0), (1.0 + 2.0 * s5 + 20.0 / 3.0) * std::exp(-2.0 * s5), 1e-15);
    // Value at r = 1: 4.9027346 · 0.1068779 = 0.5239941 (4 significant figures by hand).
    EXPECT_NEAR(matern52(1.0), 0.5240, 1e-4);
}

TEST(Matern52, DecreasesMonotonicallyTowardsZero) {
    double previous = matern52(0.0);
    for (int i = 1; i <= 2000; ++i) {
        const double value = matern52(0.005 * i);
        EXPECT_LT(value, previous) << "r = " << 0.005 * i;
        EXPECT_GT(value, 0.0);
        previous = value;
    }
    EXPECT_LT(matern52(10.0), 1e-6);
}

TEST(Matern52, RejectsNegativeOrNanDistance) {
    EXPECT_THROW(matern52(-1e-9), std::invalid_argument);
    EXPECT_THROW(matern52(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(GaussianProcess, InterpolatesASmoothFunction) {
    const int n = 10;
    Eigen::MatrixXd x(n, 1);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) {
        x(i, 0) = i / double(n - 1);
        y(i) = smooth(x(i, 0));
    }
    GpFitOptions options;
    options.noise_variance = 1e-10;
    const GaussianProcess gp = GaussianProcess::fit(x, y, options);
    EXPECT_EQ(gp.jitter(), 0.0);

    // A cubic spline through these points would be within 5/384 h⁴ max|f⁗| =
    // 5/384 (1/9)⁴ (2π)⁴ ≈ 3e-3 (h = 1/9); the GP is required to be within 0.02, about 1.3 %
    // of the range of f on [0, 1] (from −0.25 to 1.25).
    double max_mid_variance = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        const double xm = (i + 0.5) / double(n - 1);
        const GpPrediction p = gp.predict(point({xm}));
        EXPECT_NEAR(p.mean, smooth(xm), 0.02) << "x = " << xm;
        max_mid_variance = std::max(max_mid_variance, p.variance);
    }

    const double var_y = sample_variance(y);
    for (int i = 0; i < n; ++i) {
        const GpPrediction p = gp.predict(point({x(i, 0)}));
        EXPECT_NEAR(p.mean, y(i), 1e-6);
        // Latent variance at a training point: of the order of the nugget.
        EXPECT_LT(p.variance, 1e-8 * var_y);
        const double xm = (i + 0.5) / double(n - 1);
        if (i + 1 < n) {
            EXPECT_GT(gp.predict(point({xm})).variance, 1e3 * p.variance);
        }
    }
    EXPECT_GT(max_mid_variance, 0.0);
    // Outside the data the uncertainty grows beyond that between the points.
    const double outside = gp.predict(point({1.3})).variance;
    EXPECT_GT(outside, 10.0 * max_mid_variance);
    EXPECT_GT(gp.predict(point({-0.3})).variance, 10.0 * max_mid_variance);
    // And tends to the prior variance σf² s² far away.
    EXPECT_NEAR(gp.predict(point({50.0})).variance, gp.hyperparameters().signal_variance * var_y,
                1e-9 * var_y);
    EXPECT_NEAR(gp.predict(point({50.0})).mean, sample_mean(y), 1e-9);
}

TEST(GaussianProcess, EstimatesTheNoiseAndSmoothsIt) {
    const double sigma = 0.1;
    const Noisy d = noisy_smooth(sigma);
    const GaussianProcess gp = GaussianProcess::fit(d.x, d.y);
    EXPECT_GT(gp.noise_variance(), 0.5 * sigma * sigma);
    EXPECT_LT(gp.noise_variance(), 2.0 * sigma * sigma);

    double data_error = 0.0;
    double mean_error = 0.0;
    for (Eigen::Index i = 0; i < d.y.size(); ++i) {
        data_error += std::pow(d.y(i) - d.truth(i), 2);
        mean_error += std::pow(gp.predict(point({d.x(i, 0)})).mean - d.truth(i), 2);
    }
    const double n = static_cast<double>(d.y.size());
    data_error = std::sqrt(data_error / n);
    mean_error = std::sqrt(mean_error / n);
    // A smoother with about 10 effective degrees of freedom on 60 points leaves an RMS error
    // of about σ √(10/60) ≈ 0.4 σ; half the noise is a safe bound.
    EXPECT_LT(mean_error, 0.5 * data_error);
}

TEST(GaussianProcess, ArdLengthScaleOfAnIrrelevantInputIsLong) {
    const int n = 30;
    const Eigen::MatrixXd x = halton_square(n);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) y(i) = smooth(x(i, 0));
    const GaussianProcess gp = GaussianProcess::fit(x, y);
    const std::vector<double>& l = gp.hyperparameters().length_scales;
    ASSERT_EQ(l.size(), 2u);
    EXPECT_GT(l[1], 5.0 * l[0]);
    // The emulator then follows f(x0) whatever x1.
    for (const double x1 : {0.1, 0.5, 0.9}) {
        EXPECT_NEAR(gp.predict(point({0.4, x1})).mean, smooth(0.4), 0.05);
    }
}

TEST(GaussianProcess, LikelihoodAndPredictionEqualADirectComputation) {
    const Noisy d = noisy_surface();
    const GaussianProcess gp = GaussianProcess::fit(d.x, d.y);
    const GpHyperparameters& h = gp.hyperparameters();
    ASSERT_EQ(gp.jitter(), 0.0);

    const double m = sample_mean(d.y);
    const double s2 = sample_variance(d.y);
    const double s = std::sqrt(s2);
    EXPECT_NEAR(gp.output_mean(), m, 1e-14);
    EXPECT_NEAR(gp.output_scale(), s, 1e-14);
    const double n = static_cast<double>(d.y.size());
    // The density of y is that of ỹ = (y − m) / s times the Jacobian s^−n.
    const double expected = direct_standardised_log_likelihood(d.x, d.y, h) - n * std::log(s);
    EXPECT_NEAR(gp.log_marginal_likelihood(), expected, 1e-9 * std::abs(expected));
    EXPECT_NEAR(gp.noise_variance(), h.noise_variance * s2, 1e-15);

    // Predictive mean m + s k*ᵀ K⁻¹ ỹ and variance s² (k** − k*ᵀ K⁻¹ k*) (R&W eqs. 2.25–2.26).
    const Eigen::MatrixXd k = training_covariance(d.x, h);
    const Eigen::VectorXd ys = (d.y.array() - m) / s;
    const auto lu = k.fullPivLu();
    for (const Eigen::VectorXd& p : {point({0.3, 0.7}), point({0.95, 0.05}), point({1.2, -0.1})}) {
        Eigen::VectorXd k_star(d.x.rows());
        for (Eigen::Index i = 0; i < d.x.rows(); ++i) {
            k_star(i) = covariance(p, d.x.row(i).transpose(), h);
        }
        const double mean = m + s * k_star.dot(lu.solve(ys));
        const double variance = s2 * (h.signal_variance - k_star.dot(lu.solve(k_star)));
        const GpPrediction got = gp.predict(p);
        EXPECT_NEAR(got.mean, mean, 1e-9);
        EXPECT_NEAR(got.variance, variance, 1e-9 * s2);
    }
}

TEST(GaussianProcess, FittedHyperparametersMaximiseTheLikelihood) {
    for (const Noisy& d : {noisy_smooth(0.1), noisy_surface()}) {
        const GaussianProcess gp = GaussianProcess::fit(d.x, d.y);
        const GpHyperparameters best = gp.hyperparameters();
        const double at_best = direct_standardised_log_likelihood(d.x, d.y, best);
        // Each log-parameter moved by ±0.05 within its bounds lowers the likelihood.
        const auto check_moves = [&](auto&& parameter, double lo, double hi) {
            for (const double factor : {std::exp(-0.05), std::exp(0.05)}) {
                GpHyperparameters moved = best;
                double& value = parameter(moved);
                value *= factor;
                if (value >= lo && value <= hi) {
                    EXPECT_LE(direct_standardised_log_likelihood(d.x, d.y, moved), at_best + 1e-8);
                }
            }
        };
        for (std::size_t j = 0; j < best.length_scales.size(); ++j) {
            check_moves([j](GpHyperparameters& h) -> double& { return h.length_scales[j]; },
                        GaussianProcess::kMinLengthScale, GaussianProcess::kMaxLengthScale);
        }
        check_moves([](GpHyperparameters& h) -> double& { return h.signal_variance; },
                    GaussianProcess::kMinSignalVariance, GaussianProcess::kMaxSignalVariance);
        check_moves([](GpHyperparameters& h) -> double& { return h.noise_variance; },
                    GpFitOptions{}.min_noise_variance, GaussianProcess::kMaxNoiseVariance);
    }
}

TEST(GaussianProcess, KeepsAFixedNugget) {
    const Noisy d = noisy_smooth(0.1);
    GpFitOptions options;
    options.noise_variance = 1e-4;
    const GaussianProcess gp = GaussianProcess::fit(d.x, d.y, options);
    EXPECT_EQ(gp.hyperparameters().noise_variance, 1e-4);
    EXPECT_NEAR(gp.noise_variance(), 1e-4 * sample_variance(d.y), 1e-18);
}

TEST(GaussianProcess, FitIsDeterministic) {
    const Noisy d = noisy_surface();
    const GaussianProcess a = GaussianProcess::fit(d.x, d.y);
    const GaussianProcess b = GaussianProcess::fit(d.x, d.y);
    EXPECT_EQ(a.hyperparameters().length_scales, b.hyperparameters().length_scales);
    EXPECT_EQ(a.hyperparameters().signal_variance, b.hyperparameters().signal_variance);
    EXPECT_EQ(a.hyperparameters().noise_variance, b.hyperparameters().noise_variance);
    EXPECT_EQ(a.predict(point({0.2, 0.3})).mean, b.predict(point({0.2, 0.3})).mean);
}

TEST(GaussianProcess, RepeatedInputsWithoutNuggetGetJitter) {
    // x = 0.5 twice with the same y and no nugget: K is exactly singular.
    Eigen::MatrixXd x(6, 1);
    x << 0.0, 0.2, 0.5, 0.5, 0.8, 1.0;
    Eigen::VectorXd y(6);
    for (int i = 0; i < 6; ++i) y(i) = smooth(x(i, 0));
    GpFitOptions options;
    options.noise_variance = 0.0;
    const GaussianProcess gp = GaussianProcess::fit(x, y, options);
    EXPECT_GT(gp.jitter(), 0.0);
    EXPECT_LE(gp.jitter(), 1e-4 * gp.hyperparameters().signal_variance);
    const GpPrediction p = gp.predict(point({0.5}));
    EXPECT_NEAR(p.mean, smooth(0.5), 1e-3);
    EXPECT_TRUE(std::isfinite(p.variance));
}

TEST(GaussianProcess, EqualOutputsGiveTheConstant) {
    Eigen::MatrixXd x(4, 1);
    x << 0.0, 0.3, 0.6, 1.0;
    const Eigen::VectorXd y = Eigen::VectorXd::Constant(4, 2.5);
    const GaussianProcess gp = GaussianProcess::fit(x, y);
    EXPECT_NEAR(gp.predict(point({0.45})).mean, 2.5, 1e-12);
    EXPECT_NEAR(gp.predict(point({3.0})).mean, 2.5, 1e-12);
}

TEST(GaussianProcess, RejectsBadInput) {
    Eigen::MatrixXd x(3, 1);
    x << 0.0, 0.5, 1.0;
    Eigen::VectorXd y(3);
    y << 1.0, 2.0, 0.5;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();

    EXPECT_THROW(GaussianProcess::fit(x.topRows(1), y.head(1)), std::invalid_argument);
    EXPECT_THROW(GaussianProcess::fit(x, y.head(2)), std::invalid_argument);
    EXPECT_THROW(GaussianProcess::fit(Eigen::MatrixXd(3, 0), y), std::invalid_argument);
    Eigen::MatrixXd bad_x = x;
    bad_x(1, 0) = nan;
    EXPECT_THROW(GaussianProcess::fit(bad_x, y), std::invalid_argument);
    Eigen::VectorXd bad_y = y;
    bad_y(2) = inf;
    EXPECT_THROW(GaussianProcess::fit(x, bad_y), std::invalid_argument);

    GpFitOptions options;
    options.restarts = 0;
    EXPECT_THROW(GaussianProcess::fit(x, y, options), std::invalid_argument);
    options = {};
    options.min_noise_variance = 0.0;
    EXPECT_THROW(GaussianProcess::fit(x, y, options), std::invalid_argument);
    options = {};
    options.noise_variance = -1e-6;
    EXPECT_THROW(GaussianProcess::fit(x, y, options), std::invalid_argument);

    GpHyperparameters h;
    h.length_scales = {0.3, 0.3};
    EXPECT_THROW(GaussianProcess::with_hyperparameters(x, y, h), std::invalid_argument);
    h.length_scales = {-0.3};
    EXPECT_THROW(GaussianProcess::with_hyperparameters(x, y, h), std::invalid_argument);

    const GaussianProcess gp = GaussianProcess::fit(x, y);
    EXPECT_THROW(gp.predict(point({0.1, 0.2})), std::invalid_argument);
    EXPECT_THROW(gp.predict(point({nan})), std::invalid_argument);
}

/// ∫ max(best − y, 0) φ((y − mean)/sd)/sd dy over mean ± 8 sd by the trapezoid rule.
double integrated_improvement(double best, double mean, double sd) {
    const int steps = 200000;
    const double a = mean - 8.0 * sd;
    const double h = 16.0 * sd / steps;
    double sum = 0.0;
    for (int i = 0; i <= steps; ++i) {
        const double yv = a + i * h;
        const double z = (yv - mean) / sd;
        const double f =
            std::max(best - yv, 0.0) * std::exp(-0.5 * z * z) / (sd * std::sqrt(2.0 * kPi));
        sum += (i == 0 || i == steps) ? 0.5 * f : f;
    }
    return sum * h;
}

TEST(ExpectedImprovement, EqualsTheIntegralOfTheImprovement) {
    struct Case {
        double best, mean, sd;
    };
    for (const Case c : {Case{0.0, 0.0, 1.0}, Case{1.0, 0.3, 0.5}, Case{-1.0, 0.5, 0.2},
                         Case{2.0, 1.0, 3.0}, Case{0.5, 1.5, 2.0}, Case{10.0, -3.0, 0.7}}) {
        EXPECT_NEAR(expected_improvement(c.best, c.mean, c.sd),
                    integrated_improvement(c.best, c.mean, c.sd), 1e-8 * c.sd)
            << c.best << " " << c.mean << " " << c.sd;
    }
    // At best = mean: sd φ(0) = sd / √(2π).
    EXPECT_NEAR(expected_improvement(1.0, 1.0, 0.4), 0.4 / std::sqrt(2.0 * kPi), 1e-15);
}

TEST(ExpectedImprovement, WithoutUncertaintyIsThePlainImprovement) {
    EXPECT_EQ(expected_improvement(1.0, 0.25, 0.0), 0.75);
    EXPECT_EQ(expected_improvement(0.25, 1.0, 0.0), 0.0);
    EXPECT_EQ(expected_improvement(1.0, 1.0, 0.0), 0.0);
}

TEST(ExpectedImprovement, RejectsBadArguments) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(expected_improvement(0.0, 0.0, -1.0), std::invalid_argument);
    EXPECT_THROW(expected_improvement(0.0, 0.0, nan), std::invalid_argument);
    EXPECT_THROW(expected_improvement(nan, 0.0, 1.0), std::invalid_argument);
    EXPECT_THROW(expected_improvement(0.0, std::numeric_limits<double>::infinity(), 1.0),
                 std::invalid_argument);
}

}  // namespace
}  // namespace sb::correlation

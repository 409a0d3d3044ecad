#include "correlation/emulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <random>
#include <stdexcept>

#include "correlation/space_filling.hpp"

namespace sb::correlation {
namespace {

constexpr int kDraws = 96;

}  // namespace

FeatureEmulator::FeatureEmulator(const Measurement& measurement,
                                 const std::vector<FreeParameter>& free,
                                 const std::vector<Evaluation>& history)
    : measurement_(&measurement) {
    std::vector<const Evaluation*> good;
    for (const auto& e : history) {
        if (!e.error.empty() || e.simulated.value.size() != measurement.features.size()) continue;
        const bool duplicate = std::any_of(good.begin(), good.end(),
                                           [&](const Evaluation* g) { return g->key == e.key; });
        if (!duplicate) good.push_back(&e);
    }
    const auto n = static_cast<Eigen::Index>(good.size());
    if (n < 3) throw std::invalid_argument("the emulator needs at least 3 successful evaluations");
    trained_on_ = static_cast<int>(n);
    for (const auto* e : good) fillings_ = std::max(fillings_, e->simulated.fillings);
    const auto d = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd x(n, d);
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto u = to_unit(free, good[i]->values);
        for (Eigen::Index j = 0; j < d; ++j) x(i, j) = u[j];
    }
    const std::size_t features = measurement.features.size();
    processes_.resize(features);
    constant_.assign(features, 0.0);
    simulated_sigma_.assign(features, 0.0);
    for (std::size_t k = 0; k < features; ++k) {
        Eigen::VectorXd y(n);
        double sigma2 = 0.0;
        for (Eigen::Index i = 0; i < n; ++i) {
            double v = good[i]->simulated.value[k];
            if (!std::isfinite(v)) v = std::numeric_limits<double>::quiet_NaN();
            y(i) = v;
            sigma2 += std::pow(good[i]->simulated.sigma[k], 2);
        }
        simulated_sigma_[k] = std::sqrt(sigma2 / static_cast<double>(n));
        // A feature some simulations could not give (an estimate that failed) is emulated on
        // the others; with fewer than 3 it is held at the measured value plus the missing
        // residual, so the misfit still counts it.
        std::vector<Eigen::Index> rows;
        for (Eigen::Index i = 0; i < n; ++i) {
            if (std::isfinite(y(i))) rows.push_back(i);
        }
        if (rows.size() < 3) {
            const auto& f = measurement.features[k];
            constant_[k] = f.value + kMissingResidual * f.sigma;
            continue;
        }
        Eigen::MatrixXd xk(static_cast<Eigen::Index>(rows.size()), d);
        Eigen::VectorXd yk(static_cast<Eigen::Index>(rows.size()));
        for (std::size_t r = 0; r < rows.size(); ++r) {
            xk.row(static_cast<Eigen::Index>(r)) = x.row(rows[r]);
            yk(static_cast<Eigen::Index>(r)) = y(rows[r]);
        }
        const double spread = yk.maxCoeff() - yk.minCoeff();
        if (!(spread > 1e-12 * std::max(1.0, std::abs(yk.mean())))) {
            constant_[k] = yk.mean();
            continue;
        }
        GpFitOptions fit;
        fit.restarts = 8;  // more starts: a length scale stuck short invents a dependence
        // The nugget is at least the simulation's own scatter, known from its fillings: a DEM
        // campaign's features jitter with the seed, and an emulator that interpolated the
        // jitter would carve false narrow valleys into the misfit.
        double scatter2 = 0.0;
        for (const auto r : rows) scatter2 += std::pow(good[r]->simulated.sigma[k], 2);
        scatter2 /= static_cast<double>(rows.size());
        const double centred =
            (yk.array() - yk.mean()).square().sum() / static_cast<double>(yk.size() - 1);
        fit.min_noise_variance = std::clamp(scatter2 / centred, fit.min_noise_variance,
                                            0.5 * GaussianProcess::kMaxNoiseVariance);
        processes_[k] = std::make_unique<GaussianProcess>(GaussianProcess::fit(xk, yk, fit));
    }
    std::mt19937_64 generator(20261202);
    std::normal_distribution<double> normal(0.0, 1.0);
    draws_.assign(kDraws, std::vector<double>(features));
    for (auto& draw : draws_) {
        for (auto& z : draw) z = normal(generator);
    }
}

void FeatureEmulator::predict(const std::vector<double>& u, std::vector<double>& mean,
                              std::vector<double>& variance) const {
    const std::size_t features = processes_.size();
    mean.assign(features, 0.0);
    variance.assign(features, 0.0);
    Eigen::VectorXd x(static_cast<Eigen::Index>(u.size()));
    for (std::size_t j = 0; j < u.size(); ++j) x(static_cast<Eigen::Index>(j)) = u[j];
    for (std::size_t k = 0; k < features; ++k) {
        if (!processes_[k]) {
            mean[k] = constant_[k];
            continue;
        }
        const GpPrediction p = processes_[k]->predict(x);
        mean[k] = p.mean;
        variance[k] = std::max(0.0, p.variance);
    }
}

std::vector<double> FeatureEmulator::residuals(const std::vector<double>& u) const {
    std::vector<double> mean;
    std::vector<double> variance;
    predict(u, mean, variance);
    std::vector<double> r(mean.size());
    for (std::size_t k = 0; k < mean.size(); ++k) {
        r[k] = residual(measurement_->features[k], mean[k], simulated_sigma_[k], fillings_);
    }
    return r;
}

double FeatureEmulator::misfit(const std::vector<double>& u) const {
    double m = 0.0;
    for (double r : residuals(u)) m += 0.5 * r * r;
    return m;
}

double FeatureEmulator::expected_improvement(const std::vector<double>& u, double best) const {
    std::vector<double> mean;
    std::vector<double> variance;
    predict(u, mean, variance);
    double sum = 0.0;
    std::vector<double> sd(mean.size());
    for (std::size_t k = 0; k < mean.size(); ++k) sd[k] = std::sqrt(variance[k]);
    for (const auto& draw : draws_) {
        double m = 0.0;
        for (std::size_t k = 0; k < mean.size(); ++k) {
            const double r = residual(measurement_->features[k], mean[k] + sd[k] * draw[k],
                                      simulated_sigma_[k], fillings_);
            m += 0.5 * r * r;
        }
        sum += std::max(0.0, best - m);
    }
    return sum / static_cast<double>(draws_.size());
}

std::vector<double> least_emulated_misfit(const FeatureEmulator& emulator,
                                          const std::vector<FreeParameter>& free,
                                          const std::vector<double>& near) {
    const int d = static_cast<int>(free.size());
    std::vector<double> best = near;
    double least = emulator.misfit(near);
    auto pool = halton(2048, d);
    for (const auto& z : halton(512, d, 4096)) {
        std::vector<double> u(z.size());
        for (int j = 0; j < d; ++j) u[j] = std::clamp(near[j] + 0.2 * (z[j] - 0.5), 0.0, 1.0);
        pool.push_back(u);
    }
    for (const auto& u : pool) {
        const double m = emulator.misfit(u);
        if (m < least) {
            least = m;
            best = u;
        }
    }
    nlopt::opt opt(d >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, static_cast<unsigned>(d));
    opt.set_lower_bounds(std::vector<double>(free.size(), 0.0));
    opt.set_upper_bounds(std::vector<double>(free.size(), 1.0));
    opt.set_min_objective(
        [](const std::vector<double>& u, std::vector<double>& /*gradient*/, void* data) {
            return static_cast<const FeatureEmulator*>(data)->misfit(u);
        },
        const_cast<FeatureEmulator*>(&emulator));
    opt.set_maxeval(400);
    opt.set_xtol_abs(1e-5);
    opt.set_initial_step(0.02);
    std::vector<double> u = best;
    double value = least;
    try {
        opt.optimize(u, value);
        if (value < least) best = u;
    } catch (const std::exception&) {
        // a failed local polish keeps the searched point
    }
    return best;
}

}  // namespace sb::correlation

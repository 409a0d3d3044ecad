// Synthetic plants with analytic per-period RMS dynamics for the controller tests.
#pragma once

#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>

#include "control/plant.hpp"

namespace sb::control::test {

/// First-order lag of the per-period RMS toward a steady state:
/// rms_k = rms_ss(A, f) + (rms_{k-1} - rms_ss(A, f)) * decay(f). Derived plants give the
/// steady state and may distort what is observed each period.
class LagPlant : public Plant {
  public:
    PeriodResult run_period(double amplitude, double frequency_hz) override {
        const double ss = steady_rms(amplitude, frequency_hz);
        state_ = ss + (state_ - ss) * decay(frequency_hz);
        const double rms = observe(state_);
        ++periods_;
        // Fundamental as a sine of amplitude sqrt(2) rms, reported as (sine, cosine) parts.
        return {rms, {std::complex<double>(std::numbers::sqrt2 * rms, 0.0)}};
    }
    [[nodiscard]] virtual double steady_rms(double amplitude, double frequency_hz) const = 0;
    [[nodiscard]] int periods() const { return periods_; }

  protected:
    /// Envelope decay over one period [-].
    [[nodiscard]] virtual double decay(double frequency_hz) const = 0;
    /// What the control channel shows this period given the lagged level.
    virtual double observe(double lagged) { return lagged; }
    [[nodiscard]] int period_index() const { return periods_; }

  private:
    double state_ = 0.0;  // starts at rest
    int periods_ = 0;
};

/// Linear SDOF (mass m, natural frequency fn, damping ratio zeta) under a force of amplitude
/// A; control channel = acceleration. Steady RMS = A |H_acc(f)| / sqrt(2); the transient
/// envelope decays as exp(-zeta wn t), i.e. by exp(-2 pi zeta fn / f) per forcing period.
class SdofPlant : public LagPlant {
  public:
    SdofPlant(double mass_kg, double fn_hz, double zeta) : m_(mass_kg), fn_(fn_hz), zeta_(zeta) {}
    [[nodiscard]] double accelerance(double frequency_hz) const {
        const double r = frequency_hz / fn_;
        return r * r / (m_ * std::hypot(1.0 - r * r, 2.0 * zeta_ * r));
    }
    [[nodiscard]] double steady_rms(double amplitude, double frequency_hz) const override {
        return amplitude * accelerance(frequency_hz) / std::numbers::sqrt2;
    }

  protected:
    [[nodiscard]] double decay(double frequency_hz) const override {
        return std::exp(-2.0 * std::numbers::pi * zeta_ * fn_ / frequency_hz);
    }
    double m_, fn_, zeta_;
};

/// Hardening Duffing SDOF x'' + 2 zeta wn x' + wn^2 x + gamma x^3 = (A/m) sin(wt), one-term
/// harmonic balance: X^2 [(wn^2 - w^2 + 3/4 gamma X^2)^2 + (2 zeta wn w)^2] = (A/m)^2, solved
/// for X by bisection (single-valued below fn); control channel = acceleration w^2 X / sqrt 2.
class DuffingPlant : public SdofPlant {
  public:
    DuffingPlant(double mass_kg, double fn_hz, double zeta, double gamma)
        : SdofPlant(mass_kg, fn_hz, zeta), gamma_(gamma) {}
    /// Force amplitude needed for a displacement amplitude X at w (harmonic balance).
    [[nodiscard]] double force_for(double x, double frequency_hz) const {
        const double w = 2.0 * std::numbers::pi * frequency_hz;
        const double wn = 2.0 * std::numbers::pi * fn_;
        return m_ * x * std::hypot(wn * wn - w * w + 0.75 * gamma_ * x * x, 2.0 * zeta_ * wn * w);
    }
    [[nodiscard]] double steady_rms(double amplitude, double frequency_hz) const override {
        const double w = 2.0 * std::numbers::pi * frequency_hz;
        double lo = 0.0;
        double hi = amplitude / (m_ * 2.0 * zeta_ * 2.0 * std::numbers::pi * fn_ * w);
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (force_for(mid, frequency_hz) < amplitude ? lo : hi) = mid;
        }
        return w * w * 0.5 * (lo + hi) / std::numbers::sqrt2;
    }

  private:
    double gamma_;
};

/// Linear SDOF whose RMS alternates +/- `swing` period to period (a two-period limit cycle).
class AlternatingPlant : public SdofPlant {
  public:
    AlternatingPlant(double mass_kg, double fn_hz, double zeta, double swing)
        : SdofPlant(mass_kg, fn_hz, zeta), swing_(swing) {}

  protected:
    double observe(double lagged) override {
        return lagged * (period_index() % 2 == 0 ? 1.0 + swing_ : 1.0 - swing_);
    }

  private:
    double swing_;
};

/// Linear SDOF that does not respond at all below a threshold amplitude, then jumps to the
/// linear response (particles resting below about 1 g, then fluidising).
class DeadZonePlant : public SdofPlant {
  public:
    DeadZonePlant(double mass_kg, double fn_hz, double zeta, double threshold)
        : SdofPlant(mass_kg, fn_hz, zeta), threshold_(threshold) {}
    [[nodiscard]] double steady_rms(double amplitude, double frequency_hz) const override {
        return amplitude < threshold_ ? 0.0 : SdofPlant::steady_rms(amplitude, frequency_hz);
    }

  private:
    double threshold_;
};

/// Linear gain with a uniformly random +/- `scatter` on every period (chaotic response):
/// no lag, no memory, a fixed seed.
class NoisyPlant : public LagPlant {
  public:
    NoisyPlant(double gain, double scatter, std::uint64_t seed)
        : gain_(gain), scatter_(scatter), rng_(seed) {}
    [[nodiscard]] double steady_rms(double amplitude, double) const override {
        return gain_ * amplitude;
    }

  protected:
    [[nodiscard]] double decay(double) const override { return 0.0; }
    double observe(double lagged) override {
        std::uniform_real_distribution<double> u(-scatter_, scatter_);
        return lagged * (1.0 + u(rng_));
    }

  private:
    double gain_, scatter_;
    std::mt19937_64 rng_;
};

/// Linear gain whose response creeps up by `creep` (relative) every period simulated,
/// whatever the amplitude (slow drift, e.g. particles slowly rearranging).
class DriftingPlant : public LagPlant {
  public:
    DriftingPlant(double gain, double creep) : gain_(gain), creep_(creep) {}
    [[nodiscard]] double steady_rms(double amplitude, double) const override {
        return gain_ * amplitude;
    }

  protected:
    [[nodiscard]] double decay(double) const override { return 0.0; }
    double observe(double lagged) override {
        return lagged * (1.0 + creep_ * static_cast<double>(period_index()));
    }

  private:
    double gain_, creep_;
};

}  // namespace sb::control::test

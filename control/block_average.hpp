// Internal to control/: periods averaged into the values a window judges (an analyser's
// averages), shared by the amplitude controller and the fixed drive.
#pragma once

#include <complex>
#include <optional>
#include <span>
#include <vector>

namespace sb::control {

/// Groups consecutive periods into blocks of ControllerOptions::average_periods: a block's
/// value is the mean of its periods' RMS and its phasor the mean of their fundamentals. A
/// response that scatters from period to period (one sphere bouncing chaotically in its gap)
/// never holds a window of single periods within a tolerance, but the means of blocks of
/// periods converge as a swept-sine analyser's averages do; the window then judges those.
/// With blocks of one period the values are the periods' own.
class BlockAverage {
  public:
    explicit BlockAverage(int periods) : periods_(periods) {}

    /// Adds one period: its RMS, and its control fundamental when the phase test uses it.
    /// True when this period completes a block; value() and fundamental() then hold it until
    /// the next add().
    bool add(double rms, const std::complex<double>* fundamental) {
        if (count_ == periods_) clear();
        rms_sum_ += rms;
        if (fundamental != nullptr) {
            fundamental_sum_ += *fundamental;
            ++fundamentals_;
        }
        return ++count_ == periods_;
    }

    /// The completed block's mean RMS [channel unit].
    [[nodiscard]] double value() const { return rms_sum_ / static_cast<double>(count_); }

    /// The completed block's mean fundamental, when every period of it gave one.
    [[nodiscard]] std::optional<std::complex<double>> fundamental() const {
        if (fundamentals_ != count_) return std::nullopt;
        return fundamental_sum_ / static_cast<double>(count_);
    }

    /// Drops a partly filled block (the amplitude or the frequency changed).
    void clear() {
        count_ = 0;
        fundamentals_ = 0;
        rms_sum_ = 0.0;
        fundamental_sum_ = 0.0;
    }

  private:
    int periods_;
    int count_ = 0;
    int fundamentals_ = 0;
    double rms_sum_ = 0.0;
    std::complex<double> fundamental_sum_{};
};

/// The values a window judges since the drive last changed: one per completed block of
/// periods after the transient, its mean RMS, and its mean control fundamental when the
/// phase test has one for every value.
class WindowValues {
  public:
    explicit WindowValues(int average_periods) : block_(average_periods) {}

    /// Adds one period (as BlockAverage::add); true when it completed a block, which is then
    /// the last of values().
    bool add(double rms, const std::complex<double>* fundamental) {
        if (!block_.add(rms, fundamental)) return false;
        values_.push_back(block_.value());
        if (const auto mean = block_.fundamental()) phasors_.push_back(*mean);
        return true;
    }

    /// The blocks' mean RMS, oldest first [channel unit].
    [[nodiscard]] const std::vector<double>& values() const { return values_; }

    /// The blocks' mean fundamentals, one per value; empty when a block lacked one (the
    /// phase test is then not applied).
    [[nodiscard]] std::span<const std::complex<double>> phasors() const {
        if (phasors_.size() != values_.size()) return {};
        return phasors_;
    }

    /// Forgets every value and the partly filled block (the amplitude or frequency changed).
    void clear() {
        values_.clear();
        phasors_.clear();
        block_.clear();
    }

  private:
    BlockAverage block_;
    std::vector<double> values_;
    std::vector<std::complex<double>> phasors_;
};

}  // namespace sb::control

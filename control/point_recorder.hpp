// Internal to control/: the bookkeeping every driven period of a point goes through, shared by
// the amplitude controller and the fixed drive.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "control/options.hpp"
#include "control/plant.hpp"
#include "control/result.hpp"

namespace sb::control {

/// Throws std::invalid_argument listing every violation of options.validate().
inline void throw_if_invalid(const ControllerOptions& options) {
    const Violations violations = options.validate();
    if (violations.empty()) return;
    std::string text = "invalid controller options:";
    for (const auto& v : violations) {
        text += "\n  " + v.key + " = " + v.value + ": " + v.constraint + " (" + v.meaning + ")";
    }
    throw std::invalid_argument(text);
}

/// Bookkeeping of one point: every period driven goes through here.
class PointRecorder {
  public:
    PointRecorder(Plant& plant, double frequency_hz, double target_rms, PointResult& result)
        : plant_(plant), frequency_hz_(frequency_hz), result_(result) {
        result_.frequency_hz = frequency_hz;
        result_.target_rms = target_rms;
    }

    double run(double amplitude) {
        if (result_.amplitude_per_period.empty() ||
            result_.amplitude_per_period.back() != amplitude) {
            result_.amplitudes_tried.push_back(amplitude);
        }
        PeriodResult period = plant_.run_period(amplitude, frequency_hz_);
        if (!(std::isfinite(period.rms) && period.rms >= 0.0)) {
            throw std::runtime_error("control: plant reported RMS " + format_value(period.rms) +
                                     " at period " + std::to_string(result_.periods_simulated) +
                                     ", frequency " + format_value(frequency_hz_) +
                                     " Hz, amplitude " + format_value(amplitude));
        }
        const double rms = period.rms;
        result_.amplitude_per_period.push_back(amplitude);
        result_.rms_per_period.push_back(rms);
        result_.periods.push_back(std::move(period));
        ++result_.periods_simulated;
        return rms;
    }

  private:
    Plant& plant_;
    double frequency_hz_;
    PointResult& result_;
};

}  // namespace sb::control

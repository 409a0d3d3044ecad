#include "measured_options.hpp"

namespace sb::apps {

void add_uncertainty_options(CLI::App& command, correlation::StatedUncertainty& stated) {
    command
        .add_option("--damping-uncertainty", stated.damping_relative,
                    "relative uncertainty of a measured damping ratio without repeats")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    command
        .add_option("--frequency-uncertainty", stated.frequency_relative,
                    "relative uncertainty of a measured natural frequency without repeats")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    command
        .add_option("--frf-uncertainty", stated.frf_relative,
                    "relative uncertainty of a measured FRF point without repeats, of |H| and "
                    "of the phase in rad")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
}

}  // namespace sb::apps

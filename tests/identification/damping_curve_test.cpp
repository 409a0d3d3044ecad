// Per-level identification of a recording, energy measures, and real external data.
#include "identification/damping_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "core/units.hpp"
#include "identification/csv_table.hpp"
#include "identification/energy.hpp"
#include "sdof_frf.hpp"

namespace sb::identification {
namespace {

/// Exact SDOF data: estimators are exact to round-off and iteration stopping, 1e-6.
constexpr double kExactTolerance = 1e-6;

Recording sdof_recording(double zeta_h, double zeta_l, double background) {
    Recording rec;
    rec.channels = {{"force", "force", "N", "shaker", ChannelRole::reference},
                    {"acc", "acceleration", "m/s^2", "damper", ChannelRole::control}};
    for (const auto& [level, zeta] : {std::pair{0.5, zeta_h}, std::pair{1.0, zeta_l}}) {
        const auto frf =
            testing::modal_accelerance(testing::grid_around(6.37, zeta + background, 31, 4.0, 0.2),
                                       {{6.37, zeta + background, 1.0}});
        for (std::size_t i = 0; i < frf.value.size(); ++i) {
            const std::complex<double> force(2.0, 0.5);
            rec.points.push_back({"H-0",
                                  level,
                                  frf.frequency_hz[i],
                                  "converged",
                                  "",
                                  {{1.0, force}, {1.0, frf.value[i] * force}}});
        }
    }
    return rec;
}

TEST(DampingCurve, IdentifiesEveryLevelByEveryMethodAndSubtractsTheRigBackground) {
    IdentifyOptions options;
    options.background_damping_ratio = 0.002;
    const auto levels = identify_recording(sdof_recording(0.03, 0.05, 0.002), options);
    ASSERT_EQ(levels.size(), 2u);
    for (const auto& [l, zeta] : {std::pair{&levels[0], 0.03}, std::pair{&levels[1], 0.05}}) {
        EXPECT_EQ(l->channel, "acc");
        for (const auto* e : {&l->half_power, &l->circle_fit, &l->rational_fraction}) {
            ASSERT_TRUE(e->ok()) << e->message;
            EXPECT_NEAR(e->damping_ratio, zeta, kExactTolerance);
            EXPECT_NEAR(e->loss_factor(), 2.0 * zeta, 2.0 * kExactTolerance);
        }
    }
    EXPECT_TRUE(std::isnan(levels[0].specific_damping_capacity));
    const auto rows = damping_rows(levels);
    EXPECT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[1].method, "circle-fit");
}

TEST(DampingCurve, SpecificDampingCapacityAtThePeakPointIsFourPiZetaTimesFnOverF) {
    // Unit modal constant = 1 kg effective mass; ψ = 2πc/(mω) = 4πζ f_n/f at any point.
    IdentifyOptions options;
    options.effective_mass_kg = 1.0;
    options.background_damping_ratio = 0.002;
    const auto levels = identify_recording(sdof_recording(0.03, 0.05, 0.002), options);
    for (const auto& [l, zeta] : {std::pair{&levels[0], 0.03}, std::pair{&levels[1], 0.05}}) {
        const double expected =
            4.0 * kPi * ((zeta + 0.002) * 6.37 / l->capacity_frequency_hz - 0.002);
        EXPECT_NEAR(l->specific_damping_capacity, expected, kExactTolerance * expected);
        EXPECT_NEAR(l->capacity_frequency_hz, 6.37, 6.37 * (zeta + 0.002) * 8.0 / 30.0);
    }
}

TEST(Energy, SpecificDampingCapacityOfAnSdofAtResonanceIsFourPiZeta) {
    const double m = 0.5, zeta = 0.04, wn = hz_to_rad_s(46.62);
    const std::complex<double> force(3.0, 0.0);
    // At ω = ωn: X = F/(i c ω), c = 2ζmωn.
    const std::complex<double> x = force / std::complex<double>(0.0, 2.0 * zeta * m * wn * wn);
    const double w = dissipated_energy_per_cycle(force, x);
    const double t = kinetic_energy_amplitude(m, wn, x);
    const double psi = specific_damping_capacity(w, t);
    EXPECT_NEAR(psi, 4.0 * kPi * zeta, 1e-12);
    EXPECT_NEAR(damping_ratio_from_capacity(psi), zeta, 1e-14);
    EXPECT_NEAR(loss_factor_from_capacity(psi), 2.0 * zeta, 1e-14);
    EXPECT_NEAR(dissipated_energy_per_cycle_from_acceleration(force, -wn * wn * x, wn), w,
                1e-12 * w);
}

TEST(ExternalData, JointedBeamResponseControlledLevelsHaveTheirFirstModeNearEightyHertz) {
    const std::filesystem::path file = std::filesystem::path(SB_SOURCE_DIR) / ".." / "shared" /
                                       "data" / "external" / "jointed-beam" /
                                       "ForcedFrequencyResponses.csv";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "external data absent: " << file;
    const auto t = detail::read_csv(file);
    // Columns: control, level index, frequency [Hz], force [N], acc amplitude, phase [rad].
    std::map<std::string, Frf> levels;
    for (const auto& r : t.rows) {
        auto& frf = levels[r[0].text + " " + r[1].text];
        const double f = detail::number(t, r[2], "frequency_Hz");
        const double force = detail::number(t, r[3], "force_N");
        const double acc = detail::number(t, r[4], "accel_amp_mps2");
        const double phase = detail::number(t, r[5], "phase_rad");
        if (!frf.frequency_hz.empty() && !(f > frf.frequency_hz.back())) continue;
        frf.frequency_hz.push_back(f);
        frf.value.push_back(std::polar(acc / force, phase));
    }
    int identified = 0;
    for (const auto& [name, frf] : levels) {
        const auto e = rational_fraction_fit(frf);
        if (!e.ok()) continue;
        ++identified;
        // Brake–Reuß beam mode 1 (README: peak in 79.0–81.2 Hz); damping of a jointed beam is
        // well below 5 %.
        EXPECT_GT(e.natural_frequency_hz, 78.0) << name;
        EXPECT_LT(e.natural_frequency_hz, 82.0) << name;
        EXPECT_GT(e.damping_ratio, 0.0) << name;
        EXPECT_LT(e.damping_ratio, 0.05) << name;
    }
    EXPECT_GT(identified, 0);
}

}  // namespace
}  // namespace sb::identification

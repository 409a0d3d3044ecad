// Per-level identification of a recording, energy measures, and real external data.
#include "identification/damping_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <vector>

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

TEST(DampingCurve, EachFillingIsItsOwnFrfAndTheLevelReportsTheirMeanAndScatter) {
    // Two fillings of one level with 2 % and 3 % damping: averaged as one FRF they would give
    // neither; apart, each is exact, and the level's row is their mean with their scatter.
    Recording rec = sdof_recording(0.02, 0.02, 0.0);
    Recording other = sdof_recording(0.03, 0.03, 0.0);
    std::erase_if(rec.points, [](const PointRow& p) { return p.level_g != 0.5; });
    for (auto p : other.points) {
        if (p.level_g != 0.5) continue;
        p.filling = 1;
        rec.points.push_back(p);
    }
    const auto levels = identify_recording(rec);
    ASSERT_EQ(levels.size(), 2u);
    EXPECT_EQ(levels[0].filling, 0);
    EXPECT_EQ(levels[1].filling, 1);
    EXPECT_NEAR(levels[0].circle_fit.damping_ratio, 0.02, kExactTolerance);
    EXPECT_NEAR(levels[1].circle_fit.damping_ratio, 0.03, kExactTolerance);
    const auto rows = damping_rows(levels);
    ASSERT_EQ(rows.size(), 2u);  // half-power and circle fit, over both fillings
    for (const auto& row : rows) {
        EXPECT_EQ(row.fillings, 2) << row.method;
        EXPECT_NEAR(row.damping_ratio, 0.025, kExactTolerance) << row.method;
        // Sample standard deviation of 0.02 and 0.03: 0.01 / sqrt(2).
        EXPECT_NEAR(row.damping_ratio_std, 0.01 / std::sqrt(2.0), kExactTolerance) << row.method;
        EXPECT_NEAR(row.natural_frequency_hz, 6.37, 1e-6 * 6.37);
        EXPECT_EQ(row.filling, -1);
    }
    const auto each = filling_damping_rows(levels);
    ASSERT_EQ(each.size(), 4u);
    EXPECT_EQ(each[0].filling, 0);
    EXPECT_EQ(each[2].filling, 1);
    EXPECT_NEAR(each[2].damping_ratio, 0.03, kExactTolerance);
    EXPECT_EQ(each[2].fillings, 1);
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

/// One level of an exact SDOF accelerance (f_n = 6.37 Hz, ζ = 0.03) on 31 points over ±4
/// half-bandwidths, whose two points nearest the resonance did not hold their level: their
/// response is 30 % low, and they say so with status `closest`.
Recording sdof_with_closest_points(std::vector<double>& corrupted_hz) {
    Recording rec;
    rec.channels = {{"force", "force", "N", "shaker", ChannelRole::reference},
                    {"acc", "acceleration", "m/s^2", "damper", ChannelRole::control}};
    const auto frf = testing::modal_accelerance(testing::grid_around(6.37, 0.03, 31, 4.0, 0.2),
                                                {{6.37, 0.03, 1.0}});
    // The grid points either side of f_n: (f − f_lo)/step = 4ζ f_n/step − 0.2 = 14.8.
    const std::size_t near[] = {14, 15};
    corrupted_hz.clear();
    for (std::size_t i = 0; i < frf.value.size(); ++i) {
        const bool bad = i == near[0] || i == near[1];
        const std::complex<double> force(2.0, 0.5);
        rec.points.push_back({"H-0",
                              2.0,
                              frf.frequency_hz[i],
                              bad ? "closest" : "converged",
                              "",
                              {{1.0, force}, {1.0, frf.value[i] * force * (bad ? 0.7 : 1.0)}}});
        if (bad) corrupted_hz.push_back(frf.frequency_hz[i]);
    }
    return rec;
}

TEST(DampingCurve, ClosestPointsAreLeftOutOfEveryFitByDefaultAndReported) {
    std::vector<double> corrupted;
    const Recording rec = sdof_with_closest_points(corrupted);
    const auto levels = identify_recording(rec);
    ASSERT_EQ(levels.size(), 1u);
    const auto& l = levels[0];
    EXPECT_EQ(l.skipped_hz, corrupted);
    EXPECT_TRUE(l.closest_used_hz.empty());
    EXPECT_EQ(l.frf.frequency_hz.size(), rec.points.size() - corrupted.size());
    for (const auto* e : {&l.half_power, &l.circle_fit, &l.rational_fraction}) {
        ASSERT_TRUE(e->ok()) << e->message;
        EXPECT_NEAR(e->damping_ratio, 0.03, kExactTolerance);
        ASSERT_EQ(e->frequencies_used_hz.size(), static_cast<std::size_t>(e->points_used));
        for (double f : e->frequencies_used_hz) {
            // On the grid of the recording, and none of the left-out points.
            bool on_grid = false;
            for (const auto& p : rec.points) on_grid = on_grid || p.frequency_hz == f;
            EXPECT_TRUE(on_grid) << f;
            for (double bad : corrupted) EXPECT_NE(f, bad);
        }
        // The points around the resonance take part: some below and some above the gap.
        EXPECT_LT(e->frequencies_used_hz.front(), corrupted.front());
        EXPECT_GT(e->frequencies_used_hz.back(), corrupted.back());
    }
    const auto rows = damping_rows(levels, true);
    ASSERT_EQ(rows.size(), 3u);
    for (const auto& [row, e] :
         {std::pair{&rows[0], &l.half_power}, std::pair{&rows[1], &l.circle_fit},
          std::pair{&rows[2], &l.rational_fraction}}) {
        EXPECT_EQ(row->points_skipped, 2);
        EXPECT_EQ(row->points_used, e->points_used);
        EXPECT_EQ(row->frequencies_used_hz, e->frequencies_used_hz);
    }
}

TEST(DampingCurve, ClosestPointsKeptOnRequestChangeTheEstimateAndAreFlagged) {
    std::vector<double> corrupted;
    IdentifyOptions options;
    options.closest = ClosestPolicy::use;
    const auto levels = identify_recording(sdof_with_closest_points(corrupted), options);
    ASSERT_EQ(levels.size(), 1u);
    const auto& l = levels[0];
    EXPECT_TRUE(l.skipped_hz.empty());
    EXPECT_EQ(l.closest_used_hz, corrupted);
    EXPECT_EQ(l.frf.frequency_hz.size(), 31u);
    // A 30 % dip at the peak is far outside the exact estimators' tolerance: each method
    // either refuses or returns a damping ratio at least 1 % off, and one at least returns a
    // number (else the comparison would prove nothing).
    int numbers = 0;
    for (const auto* e : {&l.half_power, &l.circle_fit, &l.rational_fraction}) {
        if (!e->ok()) continue;
        ++numbers;
        EXPECT_GT(std::abs(e->damping_ratio - 0.03), 0.01 * 0.03);
    }
    EXPECT_GT(numbers, 0);
    for (const auto& row : damping_rows(levels, true)) EXPECT_EQ(row.points_skipped, 0);
}

TEST(DampingCurve, ALevelWhosePointsAreAllClosestKeepsItsPlaceAndRefusesEveryEstimate) {
    std::vector<double> corrupted;
    Recording rec = sdof_with_closest_points(corrupted);
    for (auto& p : rec.points) p.status = "closest";
    const auto levels = identify_recording(rec);
    ASSERT_EQ(levels.size(), 1u);
    EXPECT_EQ(levels[0].skipped_hz.size(), rec.points.size());
    EXPECT_TRUE(levels[0].frf.value.empty());
    for (const auto* e :
         {&levels[0].half_power, &levels[0].circle_fit, &levels[0].rational_fraction}) {
        EXPECT_EQ(e->status, EstimateStatus::too_few_points) << e->message;
    }
    EXPECT_TRUE(damping_rows(levels, true).empty());
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

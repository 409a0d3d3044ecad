// Paper 002's claims on a bed small enough for CI: at the paper's DEM condition (120 Hz,
// 10.5 g peak) the damper with the obstacle grid dissipates more than the one without,
// though it holds less (paper 002, section 4.1: 2.48 times), and so the beam carrying it
// resonates lower once the drive takes the damper past the loss factors' cross-over (paper
// 002, Table 2 and Fig. 14; docs/validation.md, paper 002). And what caps paper 002's Table 2
// on our beam: at twice gravity the bed lifts and lands as one completely inelastic block,
// whatever its contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "bench/campaign_config.hpp"
#include "bench/characterization.hpp"
#include "bench/describing_function.hpp"
#include "bench/prediction.hpp"
#include "campaign_fixtures.hpp"
#include "core/text_file.hpp"
#include "core/units.hpp"

namespace sb::bench {
namespace {

/// The shipped paper-002 damper shrunk to a 15 x 15 x 25 mm cavity (an eighth of the
/// volume): without the grid 650 spheres (what pours in, 0.52 of the cavity, at the paper's
/// 90 % fill), with it 526 (the paper's 153 / 189 of that); the grid's nodes off the centre so
/// that the rods stand 2.5 and 7.5 mm from the axis (those at 7.5 mm lie on the walls).
CampaignConfig small_bed_config(bool grid, const std::vector<std::string>& more = {}) {
    auto config = load_campaign_config(std::string(SB_SOURCE_DIR) + "/configs/paper002-" +
                                       (grid ? "grid" : "nogrid") + ".toml");
    std::vector<std::string> changes{
        "dampers.pd.enclosure.length_x_m=0.015", "dampers.pd.enclosure.length_y_m=0.015",
        "dampers.pd.enclosure.height_m=0.025",
        std::string("dampers.pd.particles.count=") + (grid ? "526" : "650")};
    if (grid) changes.push_back("dampers.pd.enclosure.rods.origin_m=[0.0025, 0.0025, 0.0]");
    changes.insert(changes.end(), more.begin(), more.end());
    apply_overrides(config, changes);
    return config;
}

/// The small bed characterised at these peak accelerations [g] and frequencies.
CharacterizeResult small_bed(bool grid, const std::vector<double>& peaks_g = {10.5},
                             const std::vector<double>& frequencies_hz = {120.0}, int seeds = 2,
                             const std::vector<std::string>& more = {}) {
    const auto config = small_bed_config(grid, more);
    CharacterizeOptions options;
    for (const double peak : peaks_g) options.levels_g.push_back(peak / std::sqrt(2.0));  // RMS
    options.frequencies_hz = frequencies_hz;
    options.seeds = seeds;
    options.threads = 2;
    return characterize(config, options);
}

/// Where the beam's resonance peaks: the largest acceleration amplitude at the damper over
/// the sweep, its frequency and the status of that point.
struct ResonancePeak {
    double acceleration_m_s2 = 0.0;
    double frequency_hz = 0.0;
    std::string status;
};

/// Paper 002's beam carrying the small bed of `table` as its describing function, driven at
/// a fixed base acceleration of `drive_m_s2` (peak) at the pin, predicted every 0.25 Hz over
/// 106-120 Hz.
ResonancePeak predicted_peak(bool grid, const CharacterizationTable& table, double drive_m_s2,
                             const std::string& name) {
    auto config = small_bed_config(grid);
    std::ostringstream grid_hz;
    grid_hz << "campaign.frequencies.values_hz=[";
    for (int k = 0; k <= 56; ++k) grid_hz << (k > 0 ? ", " : "") << 106.0 + 0.25 * k;
    grid_hz << "]";
    apply_overrides(
        config, {grid_hz.str(), "campaign.drive.amplitudes=[" + std::to_string(drive_m_s2) + "]"});
    const auto dir = test::fresh_dir("obstacle-grid-" + name);
    std::filesystem::create_directories(dir);
    const auto file = dir / "characterization.csv";
    write_file_atomically(file, characterization_csv_text(table));
    const CampaignResult result = predict_campaign(with_describing_functions(config, file), {});
    const auto at = result.recording.channel_index("acc_damper");
    EXPECT_LT(at, result.recording.channels.size());
    ResonancePeak peak;
    for (const auto& point : result.recording.points) {
        const double a = std::abs(point.values.at(at).amplitude);
        if (a > peak.acceleration_m_s2) peak = {a, point.frequency_hz, point.status};
    }
    std::filesystem::remove_all(dir);
    return peak;
}

/// The table with each point's loss moved by `sigmas` standard deviations of its fillings
/// (positive: more loss, -Im M larger).
CharacterizationTable with_loss_shifted(CharacterizationTable table, double sigmas) {
    for (auto& row : table.rows) {
        row.apparent_mass_kg -= std::complex<double>(0.0, sigmas * row.apparent_mass_im_std_kg);
    }
    return table;
}

/// A completely inelastic point mass on a floor moving as z = X sin(wt) with peak
/// acceleration gamma g (the inelastic bouncing ball, the limit a deep granular bed
/// approaches: Sack et al., Phys. Rev. Lett. 2013; Masmoudi et al., Granular Matter 2016).
/// The mass rides the floor until the floor's acceleration falls below -g, flies, lands with
/// no rebound and rides again. Per unit mass: the apparent mass M/m = -Q1/(m a1), Q the force
/// on the floor (-m(a + g) while riding, the landing impulse m(v - v_floor) at touch-down),
/// and the loss factor from the landings' kinetic energy, W / (pi m w^2 X^2).
struct InelasticBlock {
    std::complex<double> apparent_mass;
    double loss_factor_from_landings = 0.0;
};

/// Event by event: the flight in closed form, the landing found by bisection, the fundamental
/// projected over whole periods once the orbit has settled (gamma > 1).
InelasticBlock inelastic_block(double gamma) {
    constexpr double kG = kStandardGravity;
    const double w = 2.0 * std::numbers::pi;  // M/m depends on gamma only: take f = 1 Hz
    const double x = gamma * kG / (w * w);
    const auto floor_z = [&](double t) { return x * std::sin(w * t); };
    const auto floor_v = [&](double t) { return x * w * std::cos(w * t); };
    const auto phasor = [&](double t) { return std::exp(std::complex<double>(0.0, -w * t)); };
    const double settle = 40.0;  // periods
    const double end = 240.0;
    const double step = 1e-4;  // flight bracketing step [periods]
    std::complex<double> q{};
    double landing_energy = 0.0;
    double t = 0.0;
    while (t < end) {
        // Ride the floor to lift-off, where sin(wt) first reaches 1/gamma.
        const double two_pi = 2.0 * std::numbers::pi;
        const double phase = std::fmod(w * t, two_pi);
        const double lift =
            std::sin(phase) >= 1.0 / gamma
                ? t
                : t + std::fmod(std::asin(1.0 / gamma) - phase + two_pi, two_pi) / w;
        // -(a_floor + g) e^{-iwt} over the ride, by the midpoint rule (2000 per period).
        const int n = std::max(2, static_cast<int>((lift - t) * 2000.0));
        const double h = (lift - t) / n;
        for (int k = 0; k < n; ++k) {
            const double tm = t + (k + 0.5) * h;
            if (tm >= settle) q += -(-x * w * w * std::sin(w * tm) + kG) * phasor(tm) * h;
        }
        // Fly: z(t) = z0 + v0 s - g s^2/2 until the floor meets it, bracketed after lift-off.
        const double z0 = floor_z(lift);
        const double v0 = floor_v(lift);
        const auto above = [&](double tt) {
            const double s = tt - lift;
            return z0 + v0 * s - 0.5 * kG * s * s > floor_z(tt);
        };
        double hi = lift + step;
        while (above(hi)) hi += step;
        double lo = hi - step;
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            (above(mid) ? lo : hi) = mid;
        }
        const double landing = hi;
        const double relative = v0 - kG * (landing - lift) - floor_v(landing);
        if (landing >= settle) {
            q += relative * phasor(landing);
            landing_energy += 0.5 * relative * relative;
        }
        t = landing;
    }
    const double periods = t - settle;
    // The floor's acceleration -X w^2 sin(wt) = Re{i X w^2 e^{iwt}}: a1 = i X w^2.
    const std::complex<double> q1 = 2.0 * q / periods;
    const std::complex<double> a1(0.0, x * w * w);
    return {-q1 / a1, landing_energy / periods / (std::numbers::pi * w * w * x * x)};
}

TEST(ObstacleGrid, AtPaper002sDemConditionTheGridDissipatesMoreThoughItHoldsLess) {
    const auto without = small_bed(false);
    const auto with = small_bed(true);
    ASSERT_EQ(without.table.rows.size(), 1U);
    ASSERT_EQ(with.table.rows.size(), 1U);
    EXPECT_EQ(without.unsettled_runs, 0);
    EXPECT_EQ(with.unsettled_runs, 0);
    const auto& a = without.table.rows.front();
    const auto& b = with.table.rows.front();
    EXPECT_LT(b.bed_mass_kg, a.bed_mass_kg);
    // Beyond the fillings' scatter (three of the larger standard deviation): measured 0.0474
    // +- 0.0019 W against 0.0297 +- 0.0007 W over three fillings.
    const double scatter = std::max(a.power_std_w, b.power_std_w);
    EXPECT_GT(b.power_w - a.power_w, 3.0 * scatter)
        << "grid " << b.power_w << " W, without " << a.power_w << " W";
    // And per kilogram of particles, what a designer compares.
    EXPECT_GT(b.power_w / b.bed_mass_kg, 1.3 * a.power_w / a.bed_mass_kg);
}

TEST(ObstacleGrid, PastTheCrossOverTheGridLowersTheBeamsResonancePeak) {
    // Paper 002's Table 2: with the grid the beam's resonance peak at the damper is lower, at
    // every fill. Its beam drives the damper to 3-4.6 g without the grid, past the loss
    // factors' cross-over near 2.5 g (Fig. 14); from there the bed without the grid loses less
    // and less as it flies higher (-Im M of the small bed 8.1, 5.6, 4.3 g at 5, 7.5, 10.5 g
    // and 120 Hz), the grid's bed, lighter, holds its loss (8.5, 7.1, 6.6 g). The
    // beam carrying either small bed at a base drive of 5 m/s^2 (the configs' 1.316 takes it
    // to 1.7 g only, below the cross-over: docs/validation.md) was predicted to peak at
    // 91.5 m/s^2 without the grid and 68.6 m/s^2 with it.
    // Both beds in the bouncing regime at 105 and 120 Hz (the beam carrying either resonates
    // between), two fillings each.
    const auto bed_without = small_bed(false, {5.0, 7.5, 10.5}, {105.0, 120.0});
    const auto bed_with = small_bed(true, {5.0, 7.5, 10.5}, {105.0, 120.0});
    EXPECT_EQ(bed_without.unsettled_runs, 0);
    EXPECT_EQ(bed_with.unsettled_runs, 0);
    constexpr double kDrive = 5.0;  // m/s^2 at the pin
    const auto without = predicted_peak(false, bed_without.table, kDrive, "without");
    const auto with = predicted_peak(true, bed_with.table, kDrive, "with");
    // Both inside the characterised grid, past the cross-over.
    for (const auto* peak : {&without, &with}) {
        EXPECT_NE(peak->status, "extrapolated") << peak->frequency_hz;
        EXPECT_GT(peak->acceleration_m_s2, 5.0 * kStandardGravity);
        EXPECT_GT(peak->frequency_hz, 106.0);
        EXPECT_LT(peak->frequency_hz, 120.0);
    }
    EXPECT_LT(with.acceleration_m_s2, 0.85 * without.acceleration_m_s2)
        << "grid " << with.acceleration_m_s2 << ", without " << without.acceleration_m_s2;
    // Beyond the fillings' scatter: the grid's bed losing two standard deviations less at
    // every point and the open bed two more still leave the grid's peak the lower.
    const auto with_low =
        predicted_peak(true, with_loss_shifted(bed_with.table, -2.0), kDrive, "with-low");
    const auto without_high =
        predicted_peak(false, with_loss_shifted(bed_without.table, 2.0), kDrive, "without-high");
    EXPECT_LT(with_low.acceleration_m_s2, without_high.acceleration_m_s2)
        << "grid " << with_low.acceleration_m_s2 << ", without " << without_high.acceleration_m_s2;
}

TEST(InelasticBlock, TheReferenceModelRidesAsARigidMassNearLiftOffAndLosesWhatItsLandingsDo) {
    // Just above lift-off the flights are short: nearly a rigid mass. Further up the period-one
    // orbit (gamma up to about 3.7) loses the landings' kinetic energy, and the loss the force's
    // fundamental carries, -Im M/m, is that energy (two ways of counting one loss).
    const auto riding = inelastic_block(1.05);
    EXPECT_NEAR(riding.apparent_mass.real(), 1.0, 0.01);
    EXPECT_NEAR(riding.apparent_mass.imag(), 0.0, 0.01);
    for (const double gamma : {1.5, 2.04, 2.5}) {
        const auto block = inelastic_block(gamma);
        EXPECT_GT(block.loss_factor_from_landings, 0.1) << gamma;
        EXPECT_NEAR(-block.apparent_mass.imag(), block.loss_factor_from_landings,
                    0.01 * block.loss_factor_from_landings)
            << gamma;
    }
}

TEST(InelasticBlock, AtTwiceGravityTheOpenBedDissipatesAsOneBlockWhateverItsContacts) {
    // The small open bed (650 spheres, 12 layers) at 110 Hz and 2.04 g peak, contacts stiff
    // enough that the bed's own mode lies far above the drive (1e5 N/m), against the
    // completely inelastic block (M/m = 0.704 - 0.603i). Its loss within a tenth of the
    // block's, and so with a restitution of 0.97 and a third of the friction (measured
    // 0.628 and 0.591); Hertz contacts of steel, or PMMA walls, give the same within 0.04
    // (docs/validation.md, paper 002, Table 2). The in-phase part follows the block with the
    // config's contacts (0.685) and moves with the friction (0.620 at 0.1: the slippery bed
    // lands less at once). At 1.22 g the same bed is no block (0.14 of loss against the
    // block's 0.046): this is the bouncing regime's law, not any bed's.
    const std::complex<double> block = inelastic_block(2.04).apparent_mass;
    const std::vector<std::string> stiff{"dampers.pd.contact.normal_stiffness=1e5",
                                         "dampers.pd.settle.dt_s=3e-6"};
    std::vector<std::string> other = stiff;
    other.push_back("dampers.pd.contact.restitution=0.97");
    other.push_back("dampers.pd.contact.sliding_friction=0.1");
    for (const auto& changes : {stiff, other}) {
        const auto bed = small_bed(false, {2.04}, {110.0}, 1, changes);
        ASSERT_EQ(bed.table.rows.size(), 1U);
        const auto& row = bed.table.rows.front();
        const std::complex<double> ratio = row.apparent_mass_kg / row.bed_mass_kg;
        EXPECT_NEAR(ratio.imag(), block.imag(), 0.1 * std::abs(block.imag())) << changes.back();
        if (changes == stiff) {
            EXPECT_NEAR(ratio.real(), block.real(), 0.1 * block.real());
        }
    }
}

}  // namespace
}  // namespace sb::bench

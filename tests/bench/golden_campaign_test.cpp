// The golden campaign: a whole small DEM campaign whose damping curve is compared with a
// stored one, so that any change of the numbers a campaign gives shows here.
//
// One filling of the bed carries chaotic scatter (about ±10 % on the damping of paper 000's
// bed), so a single run cannot be compared with a single stored run: a change of rounding
// alone would move it by that much. The stored curve (golden/small-h0-damping.csv) is the
// mean and the sample standard deviation s of ten fillings per level, written by
//   shakerbench run tests/bench/golden/small-h0.toml --set campaign.seeds=10 --out OUT
// The test runs three other fillings (other seeds, so independent of the stored ten) and
// compares their mean with the stored mean by Student's two-sample t test: the scatter is that
// of all thirteen fillings pooled (ten fillings alone estimate it only to about a quarter,
// and the trajectories of a chaotic bed, so the ten stored fillings themselves, differ from
// one machine's floating-point library to another's), the difference of the means has the
// standard deviation s_p·sqrt(1/3 + 1/10), and the threshold is Student's quantile with 11
// degrees of freedom for a false alarm in one run of a hundred over the eight compared
// numbers (two-sided 0.125 % each: t = 4.30). A mean beyond it is a change of the physics or
// the numerics, not chance.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "bench/campaign.hpp"
#include "bench/campaign_config.hpp"
#include "bench/resolved_config.hpp"
#include "identification/recording_io.hpp"

namespace sb::bench {
namespace {

const std::string kGoldenDir = std::string(SB_SOURCE_DIR) + "/tests/bench/golden";

/// The row of `method` at `level_g` in rows over every filling, or nullptr.
const identification::DampingRow* find_row(const std::vector<identification::DampingRow>& rows,
                                           double level_g, const std::string& method) {
    for (const auto& r : rows) {
        if (r.level_g == level_g && r.method == method && r.filling < 0) return &r;
    }
    return nullptr;
}

TEST(GoldenCampaign, TheDampingCurveOfThreeNewFillingsMatchesTheStoredTenWithinTheirScatter) {
    CampaignConfig config = load_campaign_config(kGoldenDir + "/small-h0.toml");
    const auto stored = identification::read_damping_csv(kGoldenDir + "/small-h0-damping.csv");
    constexpr int kStoredFillings = 10;
    constexpr int kFillings = 3;
    // Student's t quantile, 11 degrees of freedom, one-sided 1 − 0.01 / 16.
    constexpr double kStudent = 4.30;
    set_value_text(config, "campaign.seeds", std::to_string(kFillings), "test");
    // Seeds the stored run did not use (it used seed 1 to 10).
    set_value_text(config, "campaign.seed", "1001", "test");

    CampaignContext context;
    context.threads = 2;
    const CampaignResult result = run_campaign(config, context);
    ASSERT_EQ(result.sweeps.size(), 2u * kFillings);

    int compared = 0;
    for (double level_g : config.campaign.levels_g) {
        for (const std::string method : {"half-power", "circle-fit"}) {
            const auto* reference = find_row(stored, level_g, method);
            const auto* measured = find_row(result.recording.damping, level_g, method);
            ASSERT_NE(reference, nullptr) << level_g << " g " << method << " stored";
            ASSERT_NE(measured, nullptr) << level_g << " g " << method;
            ASSERT_EQ(reference->fillings, kStoredFillings) << level_g << " g " << method;
            // Every filling resolves its estimates: the mean is over the same count.
            ASSERT_EQ(measured->fillings, kFillings) << level_g << " g " << method;
            const double sigma_of_difference = std::sqrt(1.0 / kFillings + 1.0 / kStoredFillings);
            ASSERT_GT(reference->damping_ratio_std, 0.0);
            ASSERT_GT(reference->natural_frequency_std_hz, 0.0);
            const auto pooled = [&](double stored_std, double new_std) {
                return std::sqrt(((kStoredFillings - 1) * stored_std * stored_std +
                                  (kFillings - 1) * new_std * new_std) /
                                 (kStoredFillings + kFillings - 2));
            };
            const double damping_sp =
                pooled(reference->damping_ratio_std, measured->damping_ratio_std);
            const double frequency_sp =
                pooled(reference->natural_frequency_std_hz, measured->natural_frequency_std_hz);
            std::cout << level_g << " g " << method << ": t = "
                      << (measured->damping_ratio - reference->damping_ratio) /
                             (damping_sp * sigma_of_difference)
                      << " (damping), "
                      << (measured->natural_frequency_hz - reference->natural_frequency_hz) /
                             (frequency_sp * sigma_of_difference)
                      << " (frequency); |t| <= " << kStudent << '\n';
            EXPECT_NEAR(measured->damping_ratio, reference->damping_ratio,
                        kStudent * damping_sp * sigma_of_difference)
                << level_g << " g " << method << ": stored scatter " << reference->damping_ratio_std
                << ", new " << measured->damping_ratio_std;
            EXPECT_NEAR(measured->natural_frequency_hz, reference->natural_frequency_hz,
                        kStudent * frequency_sp * sigma_of_difference)
                << level_g << " g " << method << ": stored scatter "
                << reference->natural_frequency_std_hz << ", new "
                << measured->natural_frequency_std_hz;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 4);
}

}  // namespace
}  // namespace sb::bench

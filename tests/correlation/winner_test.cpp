// The choice of the winner among fitted candidates (correlation/hypotheses.hpp): strong
// evidence by BIC, then the held-out levels as the judge between strong fits.
#include <gtest/gtest.h>

#include <vector>

#include "correlation/hypotheses.hpp"

namespace sb::correlation {
namespace {

CandidateFit fit(double bic, double held_out) {
    CandidateFit f;
    f.baseline_bic = 1000.0;
    f.bic = bic;
    f.baseline_held_out = 500.0;
    f.held_out = held_out;
    return f;
}

TEST(Winner, TheLowestBicWinsWhenItPredictsTheHeldOutLevelsAsWellAsTheOthers) {
    // Lowest BIC first, as test_hypotheses sorts them.
    EXPECT_EQ(choose_winner({fit(70.0, 14.0), fit(85.0, 13.0)}, true), 0);
    EXPECT_EQ(choose_winner({fit(70.0, 26.0), fit(85.0, 13.0)}, true), 0);  // within 2x
}

TEST(Winner, ALowerBicThatExtrapolatesWorseLosesToTheFitThatPredicts) {
    // The jointed beam: the pair fits six levels better and predicts the two held out 8x
    // worse than the power law alone.
    std::vector<CandidateFit> fits{fit(58600.0, 36600.0), fit(161000.0, 166000.0),
                                   fit(173000.0, 4420.0)};
    for (auto& f : fits) {
        f.baseline_bic = 395000.0;
        f.baseline_held_out = 139000.0;
    }
    EXPECT_EQ(choose_winner(fits, true), 2);
    // Without held-out levels the BIC alone decides.
    EXPECT_EQ(choose_winner(fits, false), 0);
}

TEST(Winner, NoneWithoutStrongEvidenceOrWhenTheHeldOutLevelsGetWorse) {
    EXPECT_EQ(choose_winner({fit(996.0, 10.0)}, true), -1);   // BIC only 4 lower
    EXPECT_EQ(choose_winner({fit(100.0, 600.0)}, true), -1);  // held out worse than baseline
    auto failed = fit(100.0, 10.0);
    failed.error = "could not be fitted";
    EXPECT_EQ(choose_winner({failed, fit(200.0, 20.0)}, true), 1);
    EXPECT_EQ(choose_winner({}, true), -1);
}

}  // namespace
}  // namespace sb::correlation

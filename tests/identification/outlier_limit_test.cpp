// The outlier limit under pose-to-pose spread of the covariances
// (host/identification/outlier_limit.h), checked against scores drawn from its model.
#include "host/identification/outlier_limit.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace h4::host {
namespace {

// n draws of f * X, X ~ chi-square(6), log f ~ N(0, spread^2).
std::vector<double> DrawScores(int n, double spread, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<double> scores;
  for (int i = 0; i < n; ++i) {
    double chi2 = 0.0;
    for (int k = 0; k < 6; ++k) chi2 += std::pow(normal(rng), 2);
    scores.push_back(std::exp(spread * normal(rng)) * chi2);
  }
  return scores;
}

TEST(OutlierLimitTest, ChiSquareSixSurvivalMatchesTables) {
  EXPECT_NEAR(ChiSquare6Survival(27.86), 1e-4, 0.01e-4);
  EXPECT_NEAR(ChiSquare6Survival(12.592), 0.05, 1e-4);
  EXPECT_NEAR(ChiSquare6Survival(5.348), 0.5, 1e-4);
  EXPECT_EQ(ChiSquare6Survival(0.0), 1.0);
}

TEST(OutlierLimitTest, NoSpreadKeepsTheChiSquareLimitAndSpreadRaisesIt) {
  EXPECT_EQ(OverdispersedLimit(27.86, 0.0), 27.86);
  double previous = 27.86;
  for (double spread : {0.2, 0.4, 0.8}) {
    const double limit = OverdispersedLimit(27.86, spread);
    EXPECT_GT(limit, previous) << spread;
    previous = limit;
  }
}

// 2 million scores drawn from the model with spread 0.6: the limit is exceeded about as
// often as chi-square(6) exceeds 27.86 (1e-4: 200 expected, Poisson sd 14).
TEST(OutlierLimitTest, LimitIsExceededAsRarelyAsTheChiSquaresUnderItsModel) {
  const double limit = OverdispersedLimit(27.86, 0.6);
  const std::vector<double> scores = DrawScores(2000000, 0.6, 17);
  int above = 0;
  for (double score : scores) above += score > limit ? 1 : 0;
  EXPECT_GT(above, 200 - 50);
  EXPECT_LT(above, 200 + 50);
  int above_chi2_limit = 0;
  for (double score : scores) above_chi2_limit += score > 27.86 ? 1 : 0;
  EXPECT_GT(above_chi2_limit, 20 * above);  // the plain limit would reject far more
}

TEST(OutlierLimitTest, SpreadIsReadFromTheQuartiles) {
  EXPECT_NEAR(ScoreSpread(DrawScores(4000, 0.6, 4)), 0.6, 0.06);
  EXPECT_NEAR(ScoreSpread(DrawScores(4000, 1.0, 5)), 1.0, 0.08);
  EXPECT_EQ(ScoreSpread({1.0, 2.0, 3.0}), 0.0);  // too few to tell
}

// Chi-square scores have no spread, but their quartiles are noisy (ln(Q3 / Q1) over 81
// scores: standard deviation about 0.11). 200 campaigns of 81 clean poses: the limit stays
// the chi-square's in about half, and under twice it in at least 90 %.
TEST(OutlierLimitTest, ChiSquareScoresRaiseTheLimitLittle) {
  int kept = 0, under_twice = 0;
  for (uint64_t campaign = 0; campaign < 200; ++campaign) {
    const double limit = OverdispersedLimit(27.86, ScoreSpread(DrawScores(81, 0.0, campaign)));
    kept += limit == 27.86 ? 1 : 0;
    under_twice += limit < 2.0 * 27.86 ? 1 : 0;
  }
  EXPECT_GE(kept, 80);
  EXPECT_GE(under_twice, 180);
}

// Gross outliers (3 % of the poses, far above the rest) move the upper quartile by about a
// percentile: the limit they leave is within a third of the clean one, two orders of
// magnitude under their scores.
TEST(OutlierLimitTest, GrossOutliersHardlyMoveTheLimit) {
  std::vector<double> scores = DrawScores(800, 0.6, 6);
  const double clean = OverdispersedLimit(27.86, ScoreSpread(scores));
  for (int i = 0; i < 24; ++i) scores[static_cast<size_t>(i)] = 1e4;
  const double with_outliers = OverdispersedLimit(27.86, ScoreSpread(scores));
  EXPECT_LT(with_outliers, clean * 4.0 / 3.0);
  EXPECT_LT(with_outliers, 1e4 / 50.0);
}

}  // namespace
}  // namespace h4::host

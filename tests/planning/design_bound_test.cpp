// Tests of the optimal-design bound (design_bound.h): on straight-line regression, whose
// L-optimal design is known in closed form, the bound is the optimum and the weights are the
// optimal design's; the certificate bounds the optimum from below even far from convergence;
// on the planning problem no design the exchange finds, nor a random one, beats it.
#include "host/planning/design_bound.h"

#include <cmath>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/pose_design.h"
#include "host/planning/pose_planner.h"
#include "tests/planning/coarse_problem.h"

namespace h4::host {
namespace {

// y = a + b x: each candidate x in [-1, 1] one row (1, x) (the first translation row of its
// 6), each evaluated pose x_e the translation row (1, x_e). Candidates 0 .. count - 1, then
// the evaluated poses.
InformationModel StraightLine(const std::vector<double>& candidates,
                              const std::vector<double>& evaluated) {
  InformationModel info;
  const auto poses = static_cast<Eigen::Index>(candidates.size() + evaluated.size());
  info.J_scaled = Eigen::MatrixXd::Zero(6 * poses, 2);
  Eigen::Index pose = 0;
  for (const std::vector<double>* xs : {&candidates, &evaluated}) {
    for (double x : *xs) info.J_scaled.row(6 * pose++ + 3) << 1.0, x;
  }
  info.sigma_t = 1.0;
  return info;
}

std::vector<double> Span(int count) {
  std::vector<double> xs;
  for (int k = 0; k < count; ++k) xs.push_back(-1.0 + 2.0 * k / (count - 1));
  return xs;
}

std::vector<int> Range(int first, int count) {
  std::vector<int> indices;
  for (int k = 0; k < count; ++k) indices.push_back(first + k);
  return indices;
}

// Predicting at x = 0.5 and 1: A = [[2, 1.5], [1.5, 1.25]]. The variance function
// (1, x) M^-1 A M^-1 (1, x)^T is convex in x, so the optimum sits at x = -1 and 1; with
// weight p at 1, M = [[1, m], [m, 1]] (m = 2p - 1) and trace(A M^-1) = (3.25 - 3 m) / (1 - m^2),
// least where 1.5 m^2 - 3.25 m + 1.5 = 0: m = 2/3, p = 5/6, trace 2.25.
TEST(OptimalDesignBound, IsTheKnownOptimumOfStraightLineRegression) {
  const std::vector<double> candidates = Span(21);
  const InformationModel info = StraightLine(candidates, {0.5, 1.0});
  BoundOptions options;
  options.pose_count = 1;  // the design measure itself: f = trace(A M(w)^-1)
  options.tolerance = 1e-9;
  options.max_iterations = 100000;
  const DesignBound bound = OptimalDesignBound(info, 21, Range(21, 2), options);
  ASSERT_TRUE(bound.converged);
  EXPECT_NEAR(bound.criterion_lower / 2.25, 1.0, 1e-6);
  EXPECT_LE(bound.criterion_lower, 2.25 * (1.0 + 1e-12)) << "a bound above the optimum";
  EXPECT_NEAR(bound.weights.back(), 5.0 / 6.0, 1e-4);
  EXPECT_NEAR(bound.weights.front(), 1.0 / 6.0, 1e-4);
  EXPECT_EQ(bound.support, (std::vector<int>{0, 20}));
}

// N poses: the criterion of N M(w) is f(w) / N, and so is the bound.
TEST(OptimalDesignBound, ScalesAsOneOverThePoseCount) {
  const InformationModel info = StraightLine(Span(21), {0.5, 1.0});
  BoundOptions options;
  options.pose_count = 4;
  options.distinct = false;  // the optimum weighs x = 1 by 5/6, above 1/4
  options.tolerance = 1e-9;
  options.max_iterations = 100000;
  EXPECT_NEAR(OptimalDesignBound(info, 21, Range(21, 2), options).criterion_lower, 2.25 / 4, 1e-6);
}

// Two distinct poses (weights at most 1/2): the bound lies between the optimum with repeats
// (2.25 / 2, 5/6 of the weight at x = 1) and the best pair of distinct candidates, found by
// brute force, and the weight at x = 1 is at the cap.
TEST(OptimalDesignBound, DistinctPosesBoundTighterThanRepeatedOnes) {
  const InformationModel info = StraightLine(Span(21), {0.5, 1.0});
  BoundOptions options;
  options.pose_count = 2;
  options.tolerance = 1e-6;
  options.max_iterations = 100000;
  const DesignBound bound = OptimalDesignBound(info, 21, Range(21, 2), options);
  double best_pair = INFINITY;
  const Eigen::MatrixXd A = InformationMatrix(info, {21, 22});
  for (int i = 0; i < 21; ++i) {
    for (int j = i + 1; j < 21; ++j) {
      best_pair = std::min(best_pair, (A * InformationMatrix(info, {i, j}).inverse()).trace());
    }
  }
  EXPECT_GT(bound.criterion_lower, 1.01 * 2.25 / 2);
  EXPECT_LE(bound.criterion_lower, best_pair * (1.0 + 1e-12));
  EXPECT_NEAR(bound.weights.back(), 0.5, 1e-9);
  options.pose_count = 22;
  EXPECT_THROW(OptimalDesignBound(info, 21, Range(21, 2), options), std::invalid_argument);
}

// Far from convergence (uniform weights, a few steps) the certificate still bounds the
// optimum from below, and lies below the weights' own criterion.
TEST(OptimalDesignBound, TheCertificateHoldsBeforeConvergence) {
  const InformationModel info = StraightLine(Span(21), {0.5, 1.0});
  for (int iterations : {0, 1, 3, 10}) {
    BoundOptions options;
    options.pose_count = 1;
    options.max_iterations = iterations;
    const DesignBound bound = OptimalDesignBound(info, 21, Range(21, 2), options);
    EXPECT_EQ(bound.iterations, iterations);
    EXPECT_LE(bound.criterion_lower, 2.25) << iterations << " iterations";
    EXPECT_GT(bound.criterion_lower, 0.0);
    EXPECT_LE(bound.criterion_lower, bound.criterion * (1.0 + 1e-12));
  }
}

// Two identical models: the mean criterion is one model's.
TEST(OptimalDesignBound, TheMeanOverIdenticalModelsIsOneModels) {
  const InformationModel info = StraightLine(Span(21), {0.5, 1.0});
  BoundOptions options;
  options.pose_count = 1;
  const DesignBound one = OptimalDesignBound(info, 21, Range(21, 2), options);
  const DesignBound two = OptimalDesignBound({&info, &info}, 21, Range(21, 2), options);
  EXPECT_NEAR(two.criterion_lower, one.criterion_lower, 1e-12);
  EXPECT_EQ(two.iterations, one.iterations);
}

// A measured pose at x = 0 (information (1, 0)^T (1, 0)), 2 poses to add: the bound (the
// Frank-Wolfe gap, f not homogeneous) stays below the best pair of candidates, found by brute
// force, and is close to it.
TEST(OptimalDesignBound, WithMeasuredPosesBoundsTheBestExactDesign) {
  const std::vector<double> candidates = Span(21);
  InformationModel info = StraightLine(candidates, {0.5, 1.0, 0.0});
  BoundOptions options;
  options.pose_count = 2;
  options.existing = {23};
  options.tolerance = 1e-6;
  options.max_iterations = 100000;
  const DesignBound bound = OptimalDesignBound(info, 21, Range(21, 2), options);
  double best = INFINITY;
  for (int i = 0; i < 21; ++i) {
    for (int j = i + 1; j < 21; ++j) {  // distinct, as the bound assumes by default
      const Eigen::MatrixXd M = InformationMatrix(info, {i, j, 23});
      const Eigen::MatrixXd A = InformationMatrix(info, {21, 22});
      if (std::abs(M.determinant()) > 1e-12) best = std::min(best, (A * M.inverse()).trace());
    }
  }
  EXPECT_LE(bound.criterion_lower, best * (1.0 + 1e-12));
  EXPECT_GT(bound.criterion_lower, 0.5 * best);
  options.existing = {3};  // a candidate
  EXPECT_THROW(OptimalDesignBound(info, 21, Range(21, 2), options), std::invalid_argument);
}

// On the planning problem: the exchange's 25 poses, and random 25, predict no better than the
// bound over the planner's models (the a priori and the drawn robots), nor over the a priori
// alone.
TEST(OptimalDesignBound, NoSeededDesignBeatsIt) {
  const PlanningProblem& problem = CoarseProblem();
  DesignBound bound;
  BoundOptions options;
  options.pose_count = 25;
  const double lower = PredictedTargetRmsBound(problem, options, &bound);
  EXPECT_GT(lower, 0.0);
  EXPECT_GT(bound.Efficiency(), 0.99);
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    EXPECT_LE(lower,
              PredictedTargetRms(problem, SeededSubset(problem.candidate_count(), 25, seed)));
  }
}

// The planner's own designs against the bound: the exchange runs over the whole coarse
// problem (over 600 s under the sanitizers, which run the planner in the PoseDesign tests and
// the bound in the ones above), hence a study (tests/CMakeLists.txt).
TEST(OptimalDesignBoundStudy, NoDesignOfThePlannerBeatsIt) {
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions design;
  design.pose_count = 25;
  BoundOptions options;
  options.pose_count = 25;
  const double lower = PredictedTargetRmsBound(problem, options);
  const PlannedCampaign planned = PlanCampaign(problem, design, 1, PlanCriterion::kAccuracy);
  EXPECT_LE(lower, planned.predicted_position_rms);
  const std::vector<int>& target = problem.target_indices;
  const Design alone = PlanForAccuracy(problem.info, problem.candidate_count(), target, design);
  BoundOptions alone_options;
  alone_options.pose_count = 25;
  const DesignBound alone_bound =
      OptimalDesignBound(problem.info, problem.candidate_count(), target, alone_options);
  const double alone_rms =
      PredictedPositionRms(problem.info, InformationMatrix(problem.info, alone.chosen), target);
  const double alone_lower = problem.info.sigma_t * std::sqrt(alone_bound.criterion_lower /
                                                              static_cast<double>(target.size()));
  EXPECT_LE(alone_lower, alone_rms);
  EXPECT_GT(alone_lower, 0.5 * alone_rms) << "a bound too loose to mean anything";
}

}  // namespace
}  // namespace h4::host

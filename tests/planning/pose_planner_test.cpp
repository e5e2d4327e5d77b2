// Tests of the planning problem's target region and of the criterion averaged over robots
// drawn from the a priori uncertainty (pose_planner.h, pose_design.h PlanForMeanAccuracy):
// the lattice spans the region, the mean over identical models is the single model's
// design, the drawn robots are other robots, and a design planned for a region predicts
// better there than one planned for another region.
#include "host/planning/pose_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

// A coarse candidate grid (100 mm, theta by 20 deg) and two drawn robots keep it short.
PlanningProblemOptions CoarseRobustOptions() {
  PlanningProblemOptions options;
  options.candidates.position_step = 0.1;
  options.candidates.theta.clear();
  for (double deg = -40.0; deg <= 40.0; deg += 20.0) {
    options.candidates.theta.push_back(RadiansFromDegrees(deg));
  }
  options.robust.robots = 2;
  options.target.positions_per_axis = 3;
  options.target.theta_count = 3;
  return options;
}

PlanningProblem RobustProblem(const PlanningProblemOptions& options) {
  return MakePlanningProblem(
      PaperAprioriRobot(),
      CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")), options);
}

const PlanningProblem& SharedRobustProblem() {
  static const PlanningProblem problem = RobustProblem(CoarseRobustOptions());
  return problem;
}

TEST(TargetRegion, TheLatticeSpansTheRegionFacesIncluded) {
  TargetRegion region;
  region.centre = Eigen::Vector3d(0.01, -0.02, -0.4);
  region.half_extent = Eigen::Vector3d(0.05, 0.04, 0.03);
  region.theta_min = RadiansFromDegrees(-10.0);
  region.theta_max = RadiansFromDegrees(30.0);
  const PosePlan poses = TargetPoses(region);
  ASSERT_EQ(poses.size(), 4u * 4u * 4u * 5u);
  EePose low = poses.front().x, high = poses.front().x;
  for (const PlannedPose& pose : poses) {
    low = low.cwiseMin(pose.x);
    high = high.cwiseMax(pose.x);
  }
  EXPECT_NEAR(low[0], -0.04, 1e-12);
  EXPECT_NEAR(high[0], 0.06, 1e-12);
  EXPECT_NEAR(low[1], -0.06, 1e-12);
  EXPECT_NEAR(high[1], 0.02, 1e-12);
  EXPECT_NEAR(low[2], -0.43, 1e-12);
  EXPECT_NEAR(high[2], -0.37, 1e-12);
  EXPECT_NEAR(low[3], region.theta_min, 1e-12);
  EXPECT_NEAR(high[3], region.theta_max, 1e-12);
  region.theta_max = region.theta_min - 0.1;
  EXPECT_THROW(TargetPoses(region), std::invalid_argument);
}

// Issue 42, defect 12: NaN and 1e160 px fell back to the constant sigmas without a word.
TEST(PlanningProblemOptions, TheCornerSigmaIsBoundedByTheCornersCsvs) {
  PlanningProblemOptions options;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;  // 0: none
  for (const double sigma : {kCornerSigmaBounds.min, 0.3, kCornerSigmaBounds.max}) {
    options.corner_sigma_px = sigma;
    EXPECT_TRUE(options.IsValid(&why)) << sigma << ": " << why;
  }
  for (const double sigma :
       {std::nan(""), 1e160, -0.5, 1e-9, 100.5, std::numeric_limits<double>::infinity()}) {
    options.corner_sigma_px = sigma;
    EXPECT_FALSE(options.IsValid(&why)) << sigma;
    EXPECT_NE(why.find("corner_sigma_px"), std::string::npos) << why;
    EXPECT_THROW(RobustProblem(options), std::invalid_argument) << sigma;
  }
}

// Issue 42, defect 13: `plan --model 12` failed on every robot tried ("forward kinematics not
// converged") unless --robust-robots 0: the robots drawn for robustness were Model 31 robots,
// whose rows a Model 12 information model was evaluated on. They are drawn in the planned
// model's parameterisation.
TEST(PosePlanner, AModel12PlanDrawsModel12Robots) {
  PlanningProblemOptions options = CoarseRobustOptions();
  options.model = ModelKind::k12;
  const PlanningProblem problem = RobustProblem(options);
  ASSERT_EQ(problem.drawn.size(), 2u);
  for (const InformationModel& drawn : problem.drawn) {
    EXPECT_EQ(drawn.model, ModelKind::k12);
    EXPECT_EQ(drawn.parameter_count(), problem.info.parameter_count());
  }
  DesignOptions design;
  design.pose_count = MinimumPlannedPoses(problem);
  EXPECT_TRUE(std::isfinite(
      PlanCampaign(problem, design, 1, PlanCriterion::kAccuracy).predicted_position_rms));
}

TEST(PlanForMeanAccuracy, IdenticalModelsGiveTheSingleModelsDesign) {
  const PlanningProblem& problem = SharedRobustProblem();
  DesignOptions options;
  options.pose_count = 20;
  const Design single =
      PlanForAccuracy(problem.info, problem.candidate_count(), problem.target_indices, options);
  const Design mean =
      PlanForMeanAccuracy({&problem.info, &problem.info, &problem.info}, problem.candidate_count(),
                          problem.target_indices, options);
  EXPECT_EQ(single.chosen, mean.chosen);
}

TEST(PosePlanner, DrawnRobotsSeeTheSamePosesThroughOtherJacobians) {
  const PlanningProblem& problem = SharedRobustProblem();
  ASSERT_EQ(problem.drawn.size(), 2u);
  ASSERT_EQ(problem.Models().size(), 3u);
  EXPECT_EQ(problem.target_lattice_size, 3 * 3 * 3 * 3);
  EXPECT_FALSE(problem.target_indices.empty());
  for (const InformationModel& drawn : problem.drawn) {
    EXPECT_EQ(drawn.pose_count(), problem.info.pose_count());
    // Another robot: its information differs from the a priori's, not by rounding.
    if (drawn.parameter_count() == problem.info.parameter_count()) {
      EXPECT_GT((drawn.J_scaled - problem.info.J_scaled).norm(),
                1e-3 * problem.info.J_scaled.norm());
    }
  }
  DesignOptions options;
  options.pose_count = 20;
  const PlannedCampaign campaign = PlanCampaign(problem, options, 1, PlanCriterion::kAccuracy);
  EXPECT_TRUE(std::isfinite(campaign.predicted_position_rms));
  EXPECT_NEAR(campaign.predicted_position_rms, PredictedTargetRms(problem, campaign.design.chosen),
              1e-15);
}

// The plan is for the user's region: planned for a small box at one side of the workspace,
// it predicts a better accuracy there than the plan for the default box does.
TEST(PosePlanner, ADesignPlannedForARegionIsBetterThere) {
  PlanningProblemOptions corner_options = CoarseRobustOptions();
  corner_options.target.centre = Eigen::Vector3d(0.08, 0.08, -0.5);
  corner_options.target.half_extent = Eigen::Vector3d(0.03, 0.03, 0.03);
  const PlanningProblem corner = RobustProblem(corner_options);
  const PlanningProblem& box = SharedRobustProblem();
  ASSERT_EQ(corner.candidate_count(), box.candidate_count());
  DesignOptions options;
  options.pose_count = 20;
  const PlannedCampaign for_corner = PlanCampaign(corner, options, 1, PlanCriterion::kAccuracy);
  const PlannedCampaign for_box = PlanCampaign(box, options, 1, PlanCriterion::kAccuracy);
  // The same candidates in the same order: the box's design evaluated on the corner.
  EXPECT_LT(for_corner.predicted_position_rms,
            0.98 * PredictedTargetRms(corner, for_box.design.chosen));
}

// A sequential campaign's second stage completes the poses measured already: planned with
// them in its information, it predicts better with them than a plan made without them
// does with them, and it counts them in its prediction.
TEST(PosePlanner, TheSecondBatchCompletesTheFirst) {
  const PlanningProblem& first_problem = SharedRobustProblem();
  DesignOptions options;
  options.pose_count = 20;
  const PlannedCampaign first = PlanCampaign(first_problem, options, 1, PlanCriterion::kAccuracy);
  PlanningProblemOptions second_options = CoarseRobustOptions();
  for (const PlannedPose& pose : first.plan) second_options.existing_poses_B.push_back(pose.x);
  const PlanningProblem second_problem = RobustProblem(second_options);
  ASSERT_EQ(second_problem.existing_indices.size(), 20u);
  ASSERT_EQ(second_problem.candidate_count(), first_problem.candidate_count());
  const PlannedCampaign second =
      PlanCampaign(second_problem, options, 101, PlanCriterion::kAccuracy);
  EXPECT_EQ(second.plan.front().pose_id, 101);
  // The same 20 poses planned again without the first batch, then measured with it.
  const PlannedCampaign blind = PlanCampaign(first_problem, options, 1, PlanCriterion::kAccuracy);
  EXPECT_LT(second.predicted_position_rms, PredictedTargetRms(second_problem, blind.design.chosen));
  // 40 poses predict better than the first 20 alone.
  EXPECT_LT(second.predicted_position_rms, 0.9 * first.predicted_position_rms);
}

// A plan at identify's minimum has no pose to spare: the planner asks for more before it
// trusts its prediction.
TEST(PosePlanner, ThePredictionIsTrustedAboveTheMinimumOnly) {
  const PlanningProblem& problem = SharedRobustProblem();
  ASSERT_EQ(problem.info.model, ModelKind::k31);
  EXPECT_GT(PosesForATrustedPrediction(problem), MinimumPlannedPoses(problem));
  EXPECT_GE(PosesForATrustedPrediction(problem),
            kTrustedPosesPerParameter * problem.info.parameter_count());
}

}  // namespace
}  // namespace h4::host

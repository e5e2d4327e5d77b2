// Tests of the D-optimal pose design and of the planning problem: the design is
// deterministic for a seed, its log det beats random designs and grid subsets of the same
// size, the exchange ends at a design no single add/drop improves, and the planned poses
// are candidates (reachable, whole board in the image).
#include "host/planning/pose_design.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/identification/identification.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/pose_planner.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"
#include "tests/planning/coarse_problem.h"

namespace h4::host {
namespace {

TEST(PoseDesign, TheSameSeedGivesTheSameDesign) {
  DesignOptions options;
  options.pose_count = 15;
  const Design a = PlanDOptimal(CoarseProblem().info, CoarseProblem().candidate_count(), options);
  const Design b = PlanDOptimal(CoarseProblem().info, CoarseProblem().candidate_count(), options);
  EXPECT_EQ(a.chosen, b.chosen);
  EXPECT_TRUE(a.converged);
  EXPECT_EQ(a.chosen.size(), 15u);
  EXPECT_EQ(std::set<int>(a.chosen.begin(), a.chosen.end()).size(), 15u) << "no pose twice";
}

TEST(PoseDesign, BeatsRandomDesignsAndTheGridOfTheSameSize) {
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions options;
  options.pose_count = 25;
  const Design design = PlanDOptimal(problem.info, problem.candidate_count(), options);
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<int> random = SeededSubset(problem.candidate_count(), 25, seed + 100);
    EXPECT_GT(design.log_det, LogDet(InformationMatrix(problem.info, random)));
  }
  const PlannedCampaign campaign = PlanCampaign(problem, options);
  EXPECT_LT(campaign.predicted_position_rms, GridPredictedPositionRms(problem, 25, 1));
  EXPECT_TRUE(std::isfinite(campaign.predicted_position_rms));
}

TEST(PoseDesign, EndsWhereAddingTheBestCandidateAndDroppingAnyPoseDoesNotHelp) {
  // DETMAX's stopping rule, checked by brute force: with the candidate that raises log det
  // most added, dropping any pose of the design (the added one aside) leaves a lower log det
  // than the design's.
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions options;
  options.pose_count = 12;
  const Design design = PlanDOptimal(problem.info, problem.candidate_count(), options);
  ASSERT_TRUE(design.converged);
  int best_added = -1;
  double best_log_det = -INFINITY;
  for (int add = 0; add < problem.candidate_count(); ++add) {
    if (std::find(design.chosen.begin(), design.chosen.end(), add) != design.chosen.end()) {
      continue;
    }
    std::vector<int> grown = design.chosen;
    grown.push_back(add);
    const double log_det = LogDet(InformationMatrix(problem.info, grown));
    if (log_det > best_log_det) {
      best_log_det = log_det;
      best_added = add;
    }
  }
  ASSERT_GE(best_added, 0);
  for (size_t drop = 0; drop < design.chosen.size(); ++drop) {
    std::vector<int> swapped = design.chosen;
    swapped[drop] = best_added;
    EXPECT_LE(LogDet(InformationMatrix(problem.info, swapped)), design.log_det + 1e-6);
  }
  const std::vector<int> start = SeededSubset(problem.candidate_count(), 12, options.seed);
  EXPECT_GT(design.log_det, LogDet(InformationMatrix(problem.info, start)));
}

TEST(PoseDesignStudy, TheAccuracyCriterionPredictsNoWorseThanDOptimality) {
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions options;
  options.pose_count = 20;
  const PlannedCampaign d = PlanCampaign(problem, options, 1, PlanCriterion::kDOptimal);
  const PlannedCampaign accuracy = PlanCampaign(problem, options, 1, PlanCriterion::kAccuracy);
  EXPECT_LE(accuracy.predicted_position_rms, d.predicted_position_rms);
  EXPECT_LT(accuracy.predicted_position_rms, GridPredictedPositionRms(problem, 20, 1));
}

// Restarts keep the best of several starts: the design of restarts = 2 is the better of
// seeds 1 and 2 alone, so never worse than the first start (here seed 2 ends higher, so
// a planner that ignored restarts would fail).
TEST(PoseDesign, RestartsKeepTheBestStart) {
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions options;
  options.pose_count = 12;
  std::vector<double> single;
  for (uint64_t seed : {1u, 2u}) {
    options.seed = seed;
    single.push_back(PlanCampaign(problem, options, 1, PlanCriterion::kDOptimal).design.log_det);
  }
  options.seed = 1;
  options.restarts = 2;
  const PlannedCampaign best = PlanCampaign(problem, options, 1, PlanCriterion::kDOptimal);
  EXPECT_EQ(best.design.log_det, std::max(single[0], single[1]));
  EXPECT_GE(best.design.log_det, single[0]);
  options.restarts = 0;
  EXPECT_THROW(PlanCampaign(problem, options, 1, PlanCriterion::kDOptimal), std::invalid_argument);
}

TEST(PoseDesign, PlannedPosesAreCandidates) {
  const PlanningProblem& problem = CoarseProblem();
  DesignOptions options;
  options.pose_count = 20;
  const PlannedCampaign campaign = PlanCampaign(problem, options, 101);
  ASSERT_EQ(campaign.plan.size(), 20u);
  EXPECT_EQ(campaign.plan.front().pose_id, 101);
  const CandidateFilter filter(
      PaperAprioriRobot(),
      CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")),
      CandidateOptions{});
  for (const PlannedPose& pose : campaign.plan) {
    EXPECT_EQ(filter.Check(pose.x, nullptr), CandidateVerdict::kOk) << pose.x.transpose();
  }
}

// Nacelle angles to +-60 deg: without the singularity rule the planner picks poses next to
// the theta singularity (they look informative there), where the simulated true robot's
// noisy joints have no forward kinematics in the a priori or fitted model, and the
// measurement-space identification cannot be evaluated ("unusable"). With the rule, the
// campaign identifies.
TEST(PoseDesign, WideThetaCampaignIdentifies) {
  PlanningProblemOptions options;
  options.candidates.position_step = 0.05;
  options.candidates.theta.clear();
  for (double deg = -60.0; deg <= 60.0; deg += 10.0) {
    options.candidates.theta.push_back(RadiansFromDegrees(deg));
  }
  const RobotDescription apriori = PaperAprioriRobot();
  const PlanningProblem problem = MakePlanningProblem(
      apriori, CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")), options);
  DesignOptions design;
  design.pose_count = 25;
  const PlannedCampaign campaign = PlanCampaign(problem, design, 1, PlanCriterion::kAccuracy);
  const SimulatedRobot truth = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31, {.seed = 1});
  DatasetOptions data;
  data.valid_count = 0;
  const SimulatedDataset dataset = SimulateDataset(truth, campaign.plan, data);
  ASSERT_TRUE(dataset.unreachable.empty());
  IdentificationOptions identification;
  identification.cross_validation.folds = 0;
  const IdentificationOutcome outcome =
      IdentifyRobot(apriori, ModelKind::k31, dataset.rows, identification);
  EXPECT_TRUE(outcome.summary.usable) << outcome.summary.message;
}

TEST(PoseDesign, AskingMorePosesThanCandidatesThrows) {
  DesignOptions options;
  options.pose_count = CoarseProblem().candidate_count() + 1;
  EXPECT_THROW(PlanDOptimal(CoarseProblem().info, CoarseProblem().candidate_count(), options),
               std::invalid_argument);
}

// Issue 27 point 4: `plan --count 1` exited 0 predicting "inf mm" for Model 31's 40 free
// parameters. A count below what identify needs is refused, saying how many.
TEST(PosePlanner, FewerPosesThanIdentifyNeedsAreRefused) {
  const PlanningProblem& problem = CoarseProblem();
  ASSERT_EQ(problem.info.model, ModelKind::k31);
  const int needed = MinimumPlannedPoses(problem);
  EXPECT_EQ(needed, 20);  // VerdictOptions::min_poses; 3 x 40 residuals / 6 is 20 too
  try {
    CheckPlannedPoseCount(problem, 1);
    ADD_FAILURE() << "one pose accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(
        std::string(e.what()).find(fmt::format("1 poses are too few: Model 31 needs at least 20 to "
                                               "identify its {} free parameters",
                                               problem.info.parameter_count())),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(CheckPlannedPoseCount(problem, needed - 1), std::invalid_argument);
  EXPECT_NO_THROW(CheckPlannedPoseCount(problem, needed));
}

// ... and with robot.yaml's forearm as long as the arm, plan failed on a grid pose the robot
// cannot reach, named "pose 1926 of the 2006" (an index into candidates and grid). The grid
// poses out of reach are left out of the prediction and listed.
TEST(PosePlanner, GridPosesOutOfTheRobotsReachAreLeftOutAndListed) {
  RobotDescription robot = PaperAprioriRobot();
  robot.model12.forearm = robot.model12.arm;
  PlanningProblemOptions options;
  options.candidates.position_step = 0.1;
  const PlanningProblem problem = MakePlanningProblem(
      robot, CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")), options);
  EXPECT_FALSE(problem.unreachable_grid_ids.empty());
  EXPECT_EQ(problem.grid.size() + problem.unreachable_grid_ids.size(), 81u);
  EXPECT_EQ(problem.grid_indices.size(), problem.grid.size());
  for (const PlannedPose& pose : problem.grid) {
    EXPECT_EQ(std::count(problem.unreachable_grid_ids.begin(), problem.unreachable_grid_ids.end(),
                         pose.pose_id),
              0);
  }
  // The prediction over the reachable grid poses is finite for a design of 25 candidates.
  ASSERT_GE(problem.candidate_count(), 25) << problem.candidates.Summary();
  DesignOptions design;
  design.pose_count = 25;
  EXPECT_TRUE(std::isfinite(PlanCampaign(problem, design).predicted_position_rms));
  EXPECT_TRUE(std::isfinite(GridPredictedPositionRms(problem, 71, 1)));  // capped at the grid
}

}  // namespace
}  // namespace h4::host

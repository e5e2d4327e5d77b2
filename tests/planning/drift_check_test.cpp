// Tests of the drift check (`h4cal check`): over simulated verification campaigns of 5
// poses with the camera noise of `h4cal simulate`, an unchanged robot passes and a robot
// whose joint offset moved enough to shift the board by 3 sigma (Mahalanobis, RMS over the
// poses) is flagged, each in at least 95 % of 20 seeded trials; and the chi-square
// quantiles are the textbook ones.
#include "host/planning/drift_check.h"

#include <cmath>

#include <gtest/gtest.h>

#include "host/simulation/dataset_simulator.h"
#include "host/simulation/paper_scenario.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

constexpr int kTrials = 20;

PosePlan CheckPoses() {
  const PosePlan grid = GridPosePlan();
  return {grid[4], grid[22], grid[40], grid[58], grid[76]};
}

SimulatedRobot Truth() {
  return MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31);
}

// The result a perfect identification would give: the truth's parameters, no uncertainty.
ParameterVector ResultOf(const SimulatedRobot& truth) {
  return ParameterVector(*truth.MakeModel(), truth.X_B31C(), truth.X_TE);
}

SimulatedRobot WithJointOffsetMoved(SimulatedRobot robot, double delta) {
  robot.model31->q0[0] += delta;
  return robot;
}

std::vector<DatasetRow> Campaign(const SimulatedRobot& robot, uint64_t seed, bool noisy) {
  DatasetOptions options;
  options.seed = seed;
  options.valid_count = 0;
  if (!noisy) options.noise = NoiseOptions{0.0, 0.0, 0.0};
  options.fill_sigma = false;  // the check's default sigmas: those of the simulated noise
  return SimulateDataset(robot, CheckPoses(), options).rows;
}

// The joint offset change that moves the noise-free board by `sigmas` (RMS Mahalanobis
// over the check poses), from the linear effect of a small change.
double JointOffsetDriftOf(double sigmas) {
  const SimulatedRobot truth = Truth();
  const double probe = 1e-5;
  const DriftCheckResult moved = CheckForDrift(
      *truth.MakeModel(), ResultOf(truth), Eigen::VectorXd::Zero(ResultOf(truth).size()),
      Campaign(WithJointOffsetMoved(truth, probe), 1, false));
  const double rms_sigmas = std::sqrt(moved.chi2 / static_cast<double>(moved.poses.size()));
  return probe * sigmas / rms_sigmas;
}

int DriftVerdicts(double joint_offset_drift) {
  const SimulatedRobot truth = Truth();
  const ParameterVector result = ResultOf(truth);
  const Eigen::VectorXd no_uncertainty = Eigen::VectorXd::Zero(result.size());
  int drift = 0;
  for (int trial = 1; trial <= kTrials; ++trial) {
    const std::vector<DatasetRow> rows = Campaign(WithJointOffsetMoved(truth, joint_offset_drift),
                                                  static_cast<uint64_t>(trial), true);
    drift += CheckForDrift(*truth.MakeModel(), result, no_uncertainty, rows).drift ? 1 : 0;
  }
  return drift;
}

TEST(DriftCheck, AnUnchangedRobotPassesInAtLeast95PercentOfTrials) {
  EXPECT_LE(DriftVerdicts(0.0), kTrials / 20);
}

TEST(DriftCheck, AThreeSigmaDriftIsFlaggedInAtLeast95PercentOfTrials) {
  const double delta = JointOffsetDriftOf(3.0);
  ASSERT_GT(delta, 0.0);
  EXPECT_GE(DriftVerdicts(delta), kTrials - kTrials / 20) << "joint offset drift " << delta;
}

TEST(DriftCheck, AGrossDriftFlagsEveryPose) {
  const SimulatedRobot truth = Truth();
  const ParameterVector result = ResultOf(truth);
  const DriftCheckResult check =
      CheckForDrift(*truth.MakeModel(), result, Eigen::VectorXd::Zero(result.size()),
                    Campaign(WithJointOffsetMoved(truth, 0.01), 1, true));
  EXPECT_TRUE(check.drift);
  for (const PoseCheck& pose : check.poses) EXPECT_TRUE(pose.flagged) << pose.pose_id;
}

TEST(DriftCheck, ParameterUncertaintyWidensWhatIsAllowed) {
  const SimulatedRobot truth = Truth();
  const ParameterVector result = ResultOf(truth);
  const std::vector<DatasetRow> rows = Campaign(WithJointOffsetMoved(truth, 1e-3), 1, true);
  const double tight =
      CheckForDrift(*truth.MakeModel(), result, Eigen::VectorXd::Zero(result.size()), rows).chi2;
  const double loose = CheckForDrift(*truth.MakeModel(), result,
                                     Eigen::VectorXd::Constant(result.size(), 1e-3), rows)
                           .chi2;
  EXPECT_LT(loose, tight);
}

TEST(DriftCheck, ChiSquareQuantilesMatchTables) {
  // Tables: chi-square(2) 0.95 -> 5.991, chi-square(6) 0.99 -> 16.812, chi-square(30) 0.95
  // -> 43.773.
  EXPECT_NEAR(ChiSquareUpperQuantileEvenDof(2, 0.05), 5.991, 1e-3);
  EXPECT_NEAR(ChiSquareUpperQuantileEvenDof(6, 0.01), 16.812, 1e-3);
  EXPECT_NEAR(ChiSquareUpperQuantileEvenDof(30, 0.05), 43.773, 1e-3);
}

}  // namespace
}  // namespace h4::host

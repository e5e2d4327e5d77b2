// Tests of the prior kinematic analysis (paper III.B): the rotation axis from the measured
// rotations alone, its per-pose spread (the 4-DoF check), and the corrected placements.
#include "host/identification/prior_analysis.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/units.h"
#include "host/kinematics/paper_robot.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return DegreesFromRadians(std::atan2(a.cross(b).norm(), a.dot(b)));
}

SimulatedDataset Simulate(const SimulatedRobot& truth, bool noise) {
  DatasetOptions options;
  if (!noise) options.noise = NoiseOptions{0.0, 0.0, 0.0};
  return SimulateDataset(truth, GridPosePlan(), options);
}

TEST(PriorAnalysisTest, FindsTheTrueAxisInCameraAndBoardFramesFromNoiseFreeRotations) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel12);
  const PriorAnalysis a =
      AnalyzeRotationAxis(Simulate(truth, false).rows, PaperX_BC(), PaperX_TE());
  ASSERT_TRUE(a.ok) << a.message;
  const Eigen::Vector3d z_B_in_C = truth.X_BC.rotation().transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_E_in_T = truth.X_TE.rotation() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(AngleDeg(a.axis_C, z_B_in_C), 1e-9);
  EXPECT_LT(AngleDeg(a.axis_T, z_E_in_T), 1e-9);
  EXPECT_LT(a.axis_spread_deg, 1e-9);
  EXPECT_EQ(a.poses_used, 81);
  // The corrected placements see z_B where the truth does; the a priori did not.
  EXPECT_GT(a.camera_axis_correction_deg, 0.1);
  EXPECT_LT(AngleDeg(a.X_BC.rotation().transpose() * Eigen::Vector3d::UnitZ(), z_B_in_C), 1e-9);
  EXPECT_LT(AngleDeg(a.X_TE.rotation() * Eigen::Vector3d::UnitZ(), z_E_in_T), 1e-9);
  // Relative angles about the axis: the grid's theta steps of 20 deg.
  ASSERT_EQ(a.relative_theta.size(), 81u);
  EXPECT_NEAR(DegreesFromRadians(std::abs(a.relative_theta[1] - a.relative_theta[0])), 20.0, 1e-6);
}

TEST(PriorAnalysisTest, AxisSpreadWithThePapersNoiseIsNearThePapersFigure) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  const PriorAnalysis a = AnalyzeRotationAxis(Simulate(truth, true).rows, PaperX_BC(), PaperX_TE());
  ASSERT_TRUE(a.ok) << a.message;
  // 0.03 deg rotation noise over 20-40 deg turns: about a tenth of a degree (paper: 0.12).
  EXPECT_GT(a.axis_spread_deg, 0.03);
  EXPECT_LT(a.axis_spread_deg, 0.3);
  const Eigen::Vector3d z_B_in_C = truth.X_BC.rotation().transpose() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(AngleDeg(a.axis_C, z_B_in_C), 0.05);
}

TEST(PriorAnalysisTest, TooFewOrUnturnedPosesAreReportedNotGuessed) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  std::vector<DatasetRow> rows = Simulate(truth, false).rows;
  const PriorAnalysis few = AnalyzeRotationAxis({rows[0], rows[1]}, PaperX_BC(), PaperX_TE());
  EXPECT_FALSE(few.ok);
  EXPECT_FALSE(few.message.empty());
  // Poses 1, 4, 7 of the grid share theta = -20 deg: no rotation between them.
  const PriorAnalysis flat =
      AnalyzeRotationAxis({rows[0], rows[3], rows[6]}, PaperX_BC(), PaperX_TE());
  EXPECT_FALSE(flat.ok);
  EXPECT_TRUE(flat.X_BC.IsNearlyEqualTo(PaperX_BC(), 0.0, 0.0));  // a priori returned
}

// Regression: comparing every pair of poses took 11 s for 8,000 rows and about two days for a
// million. The work is counted, not timed: a few relative rotations per pose.
TEST(PriorAnalysisTest, WorkIsLinearInThePoseCountAndTheAxisIsStillFound) {
  const Eigen::Vector3d axis_C = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
  const Eigen::Matrix3d R_TE =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, 1.0, 0.0).normalized()).toRotationMatrix();
  const size_t n = 8000;
  std::vector<DatasetRow> rows(n);
  for (size_t j = 0; j < n; ++j) {
    // Angles over +-40 deg in a scrambled order, so that the extremes are not rows 0 and n-1.
    const double theta = (static_cast<double>((j * 7919) % n) / n - 0.5) * RadiansFromDegrees(80.0);
    const Eigen::Matrix3d R_CT = Eigen::AngleAxisd(theta, axis_C).toRotationMatrix() * R_TE;
    rows[j].pose_id = static_cast<int64_t>(j + 1);
    rows[j].X_CT = RigidTransform(R_CT, Eigen::Vector3d(0.0, 0.0, 1.0));
  }
  const PriorAnalysis a = AnalyzeRotationAxis(rows, PaperX_BC(), PaperX_TE());
  ASSERT_TRUE(a.ok) << a.message;
  EXPECT_EQ(a.poses_used, static_cast<int>(n));
  EXPECT_LT(a.rotations_compared, static_cast<int64_t>(20 * n));
  const double sign = a.axis_C.dot(axis_C) < 0 ? -1.0 : 1.0;
  EXPECT_LT(AngleDeg(sign * a.axis_C, axis_C), 1e-6);
  EXPECT_LT(a.axis_spread_deg, 1e-6);
}

}  // namespace
}  // namespace h4::host

// Tests of Model 12 (paper eq. (1)-(2)): known joint values, closure of the inverse
// kinematics, unreachable poses, parameter vector layout and analytic Jacobians.
#include "host/kinematics/model12.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "tests/kinematics/model_test_helpers.h"

namespace h4::host {
namespace {

using testing::ExpectConstraintJacobiansMatchOffTheManifold;
using testing::ExpectParameterNames;
using testing::ExpectSetParametersTakesXiAndRefusesWrongSize;

TEST(Model12, HorizontalArmsAtTheDepthWhereForearmsCloseGivePi) {
  // At X = Y = 0, theta = 0, every PA_i = (R cos alpha_i, R sin alpha_i, Z): with the arm
  // horizontal and pointing outwards (phi = pi) the elbow is R + arm away horizontally, so
  // the forearm closes at Z = -sqrt(forearm^2 - (R + arm)^2).
  const Model12Parameters p = kPaperAprioriModel12;
  const Model12 model(p);
  const double Z = -std::sqrt(p.forearm * p.forearm - (p.R + p.arm) * (p.R + p.arm));
  const IkResult ik = model.InverseKinematics(EePose(0.0, 0.0, Z, 0.0));
  ASSERT_TRUE(ik.ok());
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(WrapAngle(ik.q[i] - std::numbers::pi), 0.0, 1e-12) << "leg " << i + 1;
  }
}

TEST(Model12, JointOffsetsShiftTheReadings) {
  Model12Parameters p = kPaperAprioriModel12;
  const EePose x(0.03, -0.05, -0.42, 0.2);
  const IkResult before = Model12(p).InverseKinematics(x);
  p.q0 = {0.1, -0.2, 0.3, -0.4};
  const IkResult after = Model12(p).InverseKinematics(x);
  ASSERT_TRUE(before.ok() && after.ok());
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(WrapAngle(before.q[i] - after.q[i] - p.q0[static_cast<size_t>(i)]), 0.0, 1e-12);
  }
}

TEST(Model12, InverseKinematicsClosesEveryLegOnThePaperGrid) {
  const Model12 model(kPaperIdentifiedModel12);
  for (const PlannedPose& pose : GridPosePlan()) {
    const IkResult ik = model.InverseKinematics(pose.x);
    ASSERT_TRUE(ik.ok()) << "pose " << pose.pose_id;
    EXPECT_LT(model.Constraints(ik.q, pose.x).cwiseAbs().maxCoeff(), 1e-14)
        << "pose " << pose.pose_id;
    for (int i = 0; i < 4; ++i) {
      EXPECT_GT(ik.q[i], -std::numbers::pi);
      EXPECT_LE(ik.q[i], std::numbers::pi);
    }
  }
}

TEST(Model12, InverseKinematicsUsesTheElbowSign) {
  const EePose x(0.02, 0.01, -0.40, 0.1);
  Assembly other;
  other.elbow = {1, 1, 1, 1};
  const IkResult a = Model12(kPaperAprioriModel12).InverseKinematics(x);
  const IkResult b = Model12(kPaperAprioriModel12, other).InverseKinematics(x);
  ASSERT_TRUE(a.ok() && b.ok());
  for (int i = 0; i < 4; ++i) EXPECT_GT(std::abs(WrapAngle(a.q[i] - b.q[i])), 0.1);
  EXPECT_LT(Model12(kPaperAprioriModel12, other).Constraints(b.q, x).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Model12, UnreachablePoseIsFlaggedWithoutNaN) {
  const Model12 model(kPaperAprioriModel12);
  const IkResult far = model.InverseKinematics(EePose(0.0, 0.0, -2.0, 0.0));
  EXPECT_FALSE(far.ok());
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(far.reachable[static_cast<size_t>(i)]);
  EXPECT_TRUE(far.q.allFinite());

  // 0.5 m along +x: legs 3 and 4 swing in the y-z plane, so their nacelle joints are at
  // least 0.5 m > forearm from any elbow; legs 1 and 2 swing in the x-z plane and reach.
  const IkResult side = model.InverseKinematics(EePose(0.5, 0.0, -0.2, 0.0));
  EXPECT_FALSE(side.ok());
  EXPECT_TRUE(side.reachable[0]);
  EXPECT_TRUE(side.reachable[1]);
  EXPECT_FALSE(side.reachable[2]);
  EXPECT_FALSE(side.reachable[3]);
  EXPECT_TRUE(side.q.allFinite());

  const IkResult nan = model.InverseKinematics(EePose(std::nan(""), 0.0, -0.45, 0.0));
  EXPECT_FALSE(nan.ok());
  EXPECT_TRUE(nan.q.allFinite());
}

TEST(Model12, ParameterVectorFollowsKinematicsMdOrder) {
  const Model12 model(kPaperIdentifiedModel12);
  ASSERT_NO_FATAL_FAILURE(
      ExpectParameterNames(model, 13, {{0, "h"}, {3, "R"}, {4, "d"}, {5, "alpha1"}, {12, "q04"}}));
  const Eigen::VectorXd xi = model.parameters();
  EXPECT_DOUBLE_EQ(xi[2], 0.4876);
  EXPECT_DOUBLE_EQ(xi[6], 3.1016);
  EXPECT_DOUBLE_EQ(xi[10], -0.0080);
  Model12 copy(kPaperAprioriModel12);
  ExpectSetParametersTakesXiAndRefusesWrongSize(copy, xi, 12);
}

class Model12Jacobians : public ::testing::TestWithParam<EePose> {};

TEST_P(Model12Jacobians, MatchFiniteDifferences) {
  const Model12 model(kPaperIdentifiedModel12);
  const EePose x = GetParam();
  JointVector q;
  ASSERT_NO_FATAL_FAILURE(ExpectConstraintJacobiansMatchOffTheManifold(
      model, x, JointVector(0.01, -0.02, 0.015, 0.005), &q));
  Eigen::Matrix4d J_f_x;
  Eigen::Vector4d J_f_q;
  Eigen::MatrixXd J_f_xi;
  model.ConstraintJacobians(q, x, &J_f_x, &J_f_q, &J_f_xi);
  EXPECT_TRUE(J_f_xi.col(4).isZero(0.0)) << "d has no influence on Model 12";
}

INSTANTIATE_TEST_SUITE_P(Poses, Model12Jacobians,
                         ::testing::ValuesIn(testing::JacobianCheckPoses()));

}  // namespace
}  // namespace h4::host

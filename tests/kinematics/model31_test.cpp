// Tests of Model 31 (paper eq. (4)): the nominal Model 31 reproduces Model 12 exactly,
// inverse kinematics closes the legs of a non-nominal robot, unreachable poses, parameter
// layout, workspace centre and analytic Jacobians.
#include "host/kinematics/model31.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "tests/kinematics/model_test_helpers.h"

namespace h4::host {
namespace {

using testing::ExpectConstraintJacobiansMatchOffTheManifold;
using testing::ExpectParameterNames;
using testing::ExpectSetParametersTakesXiAndRefusesWrongSize;

// A Model 31 robot away from the nominal one in every parameter.
Model31Parameters SkewedModel31() {
  Model31Parameters p = NominalModel31(kPaperIdentifiedModel12);
  p.P[0] += Eigen::Vector3d(0.004, -0.003, 0.002);
  p.P[1] += Eigen::Vector3d(-0.002, 0.005, -0.003);
  p.P[2] += Eigen::Vector3d(0.003, 0.002, 0.004);
  p.psi = {p.psi[0] + 0.01, p.psi[1] - 0.02, p.psi[2] + 0.015, p.psi[3] - 0.01};
  p.beta = {p.beta[0] + 0.02, p.beta[1] - 0.01, p.beta[2] + 0.03, p.beta[3] - 0.02};
  p.arm = {0.261, 0.259, 0.2605, 0.258};
  p.forearm = {0.488, 0.486, 0.489, 0.487};
  p.h = 0.0605;
  p.d = 0.012;
  return p;
}

TEST(Model31, NominalModelGivesExactlyModel12JointsOnMappedPoses) {
  for (Model12Parameters m12 : {kPaperAprioriModel12, kPaperIdentifiedModel12}) {
    m12.d = 0.035;  // d moves B31 but must not change any joint
    const Model12 model12(m12);
    const Model31 model31(NominalModel31(m12));
    const RigidTransform X_B31B = NominalX_B31B(m12);
    for (const PlannedPose& pose : GridPosePlan()) {
      const IkResult q12 = model12.InverseKinematics(pose.x);
      const IkResult q31 = model31.InverseKinematics(EePoseInB31(pose.x, X_B31B));
      ASSERT_TRUE(q12.ok() && q31.ok()) << "pose " << pose.pose_id;
      for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(WrapAngle(q31.q[i] - q12.q[i]), 0.0, 1e-12)
            << "pose " << pose.pose_id << " leg " << i + 1;
      }
    }
  }
}

TEST(Model31, PoseMapTranslatesByKinematicsMdFormula) {
  Model12Parameters m12 = kPaperIdentifiedModel12;
  m12.d = 0.02;
  const EePose x31 = EePoseInB31(EePose(0.01, 0.02, -0.4, 0.3), NominalX_B31B(m12));
  EXPECT_NEAR(x31[0], 0.01 + m12.R * std::cos(m12.alpha[0]), 1e-15);
  EXPECT_NEAR(x31[1], 0.02 + m12.R * std::sin(m12.alpha[0]) - m12.d, 1e-15);
  EXPECT_NEAR(x31[2], -0.4, 1e-15);
  EXPECT_NEAR(x31[3], 0.3, 1e-15);
}

TEST(Model31, NominalWorkspaceCentreIsModel12CentreMapped) {
  Model12Parameters m12 = kPaperIdentifiedModel12;
  m12.d = 0.02;
  const Model31 model31(NominalModel31(m12));
  const EePose expected = EePoseInB31(Model12(m12).WorkspaceCentre(), NominalX_B31B(m12));
  EXPECT_LT((model31.WorkspaceCentre() - expected).norm(), 1e-12);
}

TEST(Model31, InverseKinematicsClosesEveryLegOfASkewedRobot) {
  const Model31 model(SkewedModel31());
  const RigidTransform X_B31B = NominalX_B31B(kPaperIdentifiedModel12);
  for (const PlannedPose& pose : GridPosePlan()) {
    const EePose x = EePoseInB31(pose.x, X_B31B);
    const IkResult ik = model.InverseKinematics(x);
    ASSERT_TRUE(ik.ok()) << "pose " << pose.pose_id;
    EXPECT_LT(model.Constraints(ik.q, x).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Model31, UnreachablePoseIsFlaggedWithoutNaN) {
  const Model31 model(SkewedModel31());
  const IkResult far = model.InverseKinematics(EePose(0.14, 0.0, -2.0, 0.0));
  EXPECT_FALSE(far.ok());
  for (bool reachable : far.reachable) EXPECT_FALSE(reachable);
  EXPECT_TRUE(far.q.allFinite());
  const IkResult inf = model.InverseKinematics(EePose(0.14, INFINITY, -0.45, 0.0));
  EXPECT_FALSE(inf.ok());
  EXPECT_TRUE(inf.q.allFinite());
}

TEST(Model31, ParameterVectorFollowsKinematicsMdOrder) {
  const Model31Parameters p = SkewedModel31();
  const Model31 model(p);
  ASSERT_NO_FATAL_FAILURE(ExpectParameterNames(model, 31,
                                               {{0, "x2"},
                                                {8, "z4"},
                                                {9, "psi1"},
                                                {13, "beta1"},
                                                {17, "q01"},
                                                {21, "arm1"},
                                                {25, "forearm1"},
                                                {29, "h"},
                                                {30, "d"}}));
  const Eigen::VectorXd xi = model.parameters();
  EXPECT_DOUBLE_EQ(xi[4], p.P[1].y());
  EXPECT_DOUBLE_EQ(xi[15], p.beta[2]);
  EXPECT_DOUBLE_EQ(xi[24], p.arm[3]);
  EXPECT_DOUBLE_EQ(xi[30], p.d);
  Model31 copy(NominalModel31(kPaperAprioriModel12));
  ExpectSetParametersTakesXiAndRefusesWrongSize(copy, xi, 13);
}

class Model31Jacobians : public ::testing::TestWithParam<EePose> {};

TEST_P(Model31Jacobians, MatchFiniteDifferences) {
  const Model31 model(SkewedModel31());
  const EePose x = EePoseInB31(GetParam(), NominalX_B31B(kPaperIdentifiedModel12));
  ExpectConstraintJacobiansMatchOffTheManifold(model, x, JointVector(-0.01, 0.02, 0.005, -0.015));
}

INSTANTIATE_TEST_SUITE_P(Poses, Model31Jacobians,
                         ::testing::ValuesIn(testing::JacobianCheckPoses()));

}  // namespace
}  // namespace h4::host

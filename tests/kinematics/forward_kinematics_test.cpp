// Tests of the numerical forward kinematics: it inverts the closed-form inverse
// kinematics on the paper's grid for both models, reports failures (unreachable joints,
// non-finite input, another assembly mode) and its Jacobians by joints and parameters
// match finite differences of the solver itself.
#include "host/kinematics/forward_kinematics.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "tests/kinematics/jacobian_check_helpers.h"

namespace h4::host {
namespace {

using testing::JacobianMatchesFiniteDifferences;

Model31Parameters PerturbedModel31() {
  Model31Parameters p = NominalModel31(kPaperIdentifiedModel12);
  p.P[0] += Eigen::Vector3d(0.003, -0.002, 0.001);
  p.P[2] += Eigen::Vector3d(-0.002, 0.004, -0.002);
  p.psi[1] += 0.02;
  p.beta[3] += 0.03;
  p.arm[2] = 0.262;
  p.forearm[0] = 0.485;
  p.d = 0.01;
  return p;
}

void ExpectFkInvertsIkOnGrid(const KinematicModel& model, const RigidTransform& X_modelB) {
  for (const PlannedPose& pose : GridPosePlan()) {
    const EePose x_true = EePoseInB31(pose.x, X_modelB);
    const IkResult ik = model.InverseKinematics(x_true);
    ASSERT_TRUE(ik.ok()) << "pose " << pose.pose_id;
    const FkResult fk = ForwardKinematics(model, ik.q);
    ASSERT_TRUE(fk.ok()) << "pose " << pose.pose_id << ": " << fk.message;
    EXPECT_LT((fk.x.head<3>() - x_true.head<3>()).norm(), 1e-10) << "pose " << pose.pose_id;
    EXPECT_LT(std::abs(WrapAngle(fk.x[3] - x_true[3])), 1e-10) << "pose " << pose.pose_id;
    EXPECT_LT(fk.residual, 1e-12);
    EXPECT_LE(fk.iterations, 10);
  }
}

TEST(ForwardKinematics, InvertsModel12InverseKinematicsOnPaperGrid) {
  ExpectFkInvertsIkOnGrid(Model12(kPaperIdentifiedModel12), RigidTransform());
}

TEST(ForwardKinematics, InvertsModel31InverseKinematicsOnPaperGrid) {
  ExpectFkInvertsIkOnGrid(Model31(PerturbedModel31()), NominalX_B31B(kPaperIdentifiedModel12));
}

TEST(ForwardKinematics, StartsFromAGivenGuess) {
  const Model12 model(kPaperAprioriModel12);
  const EePose x_true(0.05, -0.04, -0.5, 0.2);
  const IkResult ik = model.InverseKinematics(x_true);
  ASSERT_TRUE(ik.ok());
  const FkResult fk = ForwardKinematics(model, ik.q, EePose(0.049, -0.041, -0.5, 0.21));
  ASSERT_TRUE(fk.ok()) << fk.message;
  EXPECT_LT((fk.x - x_true).norm(), 1e-10);
  EXPECT_LE(fk.iterations, 5);
}

TEST(ForwardKinematics, ReportsJointsThatAdmitNoPose) {
  // Short forearms (0.2 m) and all arms horizontal and outward (q = pi): the elbows of legs
  // 1 and 2 are 0.8 m apart, so their nacelle joints would be at least 0.4 m apart, but
  // the nacelle holds them within 4 h = 0.24 m of each other at any theta.
  Model12Parameters p = kPaperAprioriModel12;
  p.forearm = 0.2;
  const Model12 model(p);
  const JointVector q = JointVector::Constant(std::numbers::pi);
  const FkResult fk = ForwardKinematics(model, q);
  EXPECT_FALSE(fk.ok());
  EXPECT_EQ(fk.status, FkStatus::kNotConverged);
  EXPECT_TRUE(fk.x.allFinite());
  EXPECT_GT(fk.residual, 1e-3);
  EXPECT_NE(fk.message.find("not converged"), std::string::npos) << fk.message;
}

TEST(ForwardKinematics, ReportsNonFiniteJoints) {
  const Model12 model(kPaperAprioriModel12);
  const FkResult fk = ForwardKinematics(model, JointVector(0.0, NAN, 0.0, 0.0));
  EXPECT_EQ(fk.status, FkStatus::kInvalidInput);
  EXPECT_TRUE(fk.x.allFinite());
  EXPECT_FALSE(fk.message.empty());
}

TEST(ForwardKinematics, ReportsAnotherAssemblyModeAsWrongBranch) {
  // Joints of a robot whose leg 1 elbow is on the other branch satisfy f(q, x) = 0 at
  // x_true, but the closed-form IK of the model (eps = -1) gives other joints there.
  Assembly flipped;
  flipped.elbow = {1, -1, -1, -1};
  const EePose x_true(0.02, 0.03, -0.45, 0.1);
  const IkResult ik = Model12(kPaperAprioriModel12, flipped).InverseKinematics(x_true);
  ASSERT_TRUE(ik.ok());
  const Model12 model(kPaperAprioriModel12);
  FkOptions options;
  options.retry_from_centre = false;
  const FkResult fk = ForwardKinematics(model, ik.q, x_true, options);
  EXPECT_EQ(fk.status, FkStatus::kWrongBranch) << fk.message;
  EXPECT_FALSE(fk.ok());
}

template <typename Model>
void ExpectFkJacobiansMatchFiniteDifferences(const Model& model, const EePose& x_true) {
  const IkResult ik = model.InverseKinematics(x_true);
  ASSERT_TRUE(ik.ok());
  Eigen::Matrix4d J_x_q;
  Eigen::MatrixXd J_x_xi;
  ASSERT_TRUE(ForwardKinematicsJacobians(model, ik.q, x_true, &J_x_q, &J_x_xi));
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(
      [&](const Eigen::VectorXd& q) -> Eigen::VectorXd {
        return ForwardKinematics(model, q, x_true).x;
      },
      ik.q, J_x_q, 1e-6, 1e-7));
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(
      [&](const Eigen::VectorXd& xi) -> Eigen::VectorXd {
        Model perturbed(model);
        perturbed.set_parameters(xi);
        return ForwardKinematics(perturbed, ik.q, x_true).x;
      },
      model.parameters(), J_x_xi, 1e-6, 1e-7));
}

TEST(ForwardKinematics, Model12JacobiansMatchFiniteDifferences) {
  ExpectFkJacobiansMatchFiniteDifferences(Model12(kPaperIdentifiedModel12),
                                          EePose(0.07, -0.05, -0.4, 0.25));
}

TEST(ForwardKinematics, Model31JacobiansMatchFiniteDifferences) {
  ExpectFkJacobiansMatchFiniteDifferences(
      Model31(PerturbedModel31()),
      EePoseInB31(EePose(-0.06, 0.08, -0.5, -0.3), NominalX_B31B(kPaperIdentifiedModel12)));
}

// Its speed (the measurement-space identification solves 81 per evaluation) is measured in
// host/bench/identification_bench (BM_ForwardKinematicsPaperGrid), not asserted here.
TEST(ForwardKinematics, SolvesEveryPoseOfThePaperGridFromTheDefaultGuess) {
  const Model31 model(PerturbedModel31());
  int converged = 0;
  for (const PlannedPose& pose : GridPosePlan()) {
    const IkResult ik =
        model.InverseKinematics(EePoseInB31(pose.x, NominalX_B31B(kPaperIdentifiedModel12)));
    ASSERT_TRUE(ik.ok());
    converged += ForwardKinematics(model, ik.q).ok() ? 1 : 0;
  }
  EXPECT_EQ(converged, 81);
}

}  // namespace
}  // namespace h4::host

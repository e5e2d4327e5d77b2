// Tests of the measurement chain (eq. (6)): known board pose of the default placement,
// recovery of the end-effector pose, the tilt residual, and the predicted board pose.
#include "host/kinematics/measurement_chain.h"

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

const RigidTransform kX_BC = RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.01, -0.02, -1.04),
                                                                Eigen::Vector3d(0.02, -0.015, 0.3));
const RigidTransform kX_TE = RigidTransform::FromTranslationRpy(
    Eigen::Vector3d(0.09, 0.085, 0.027), Eigen::Vector3d(-0.01, 0.012, 0.05));

TEST(MeasurementChain, DefaultPlacementSeesBoardAboveCameraAtKnownPose) {
  const RigidTransform X_CT =
      PredictedBoardPose(PaperX_BC(), EePose(0.0, 0.0, -0.45, 0.0), PaperX_TE());
  EXPECT_LT((X_CT.translation() - Eigen::Vector3d(-0.09, -0.09, 0.575)).norm(), 1e-15);
  EXPECT_TRUE(X_CT.rotation().isIdentity(1e-15));
}

TEST(MeasurementChain, RecoversTheEndEffectorPoseWithoutTilt) {
  const EePose x(0.05, -0.07, -0.42, -0.3);
  const RigidTransform X_CT = PredictedBoardPose(kX_BC, x, kX_TE);
  const MeasuredEePose measured = EePoseFromMeasurement(kX_BC, X_CT, kX_TE);
  EXPECT_LT((measured.x - x).norm(), 1e-14);
  EXPECT_LT(measured.tilt_angle, 1e-14);
}

TEST(MeasurementChain, ReportsTiltAsRotationVectorInE) {
  const EePose x(0.0, 0.02, -0.5, 0.4);
  const Eigen::Vector3d tilt_E(0.004, -0.003, 0.0);
  const RigidTransform X_BE(RotZ(x[3]) * So3Exp(tilt_E), x.head<3>());
  const RigidTransform X_CT = kX_BC.inverse() * X_BE * kX_TE.inverse();
  const MeasuredEePose measured = EePoseFromMeasurement(kX_BC, X_CT, kX_TE);
  // A tilt without yaw component leaves atan2(R(1,0), R(0,0)) at theta to second order.
  EXPECT_NEAR(measured.x[3], x[3], 1e-5);
  EXPECT_LT((measured.tilt - tilt_E).norm(), 1e-5);
  EXPECT_NEAR(measured.tilt_angle, tilt_E.norm(), 1e-5);
  EXPECT_LT((measured.x.head<3>() - x.head<3>()).norm(), 1e-15);
}

TEST(MeasurementChain, EePoseTransformRoundTrip) {
  const EePose x(0.1, 0.2, -0.3, 3.0);
  const RigidTransform X_BE = TransformFromEePose(x);
  EXPECT_NEAR(X_BE.rotation()(1, 0), std::sin(3.0), 1e-15);
  Eigen::Vector3d tilt;
  EXPECT_LT((EePoseFromTransform(X_BE, &tilt) - x).norm(), 1e-15);
  EXPECT_LT(tilt.norm(), 1e-15);
}

}  // namespace
}  // namespace h4::host

// Rigid transforms: composition in monogram notation, inverse, pose error.
#include "common/geometry/rigid_transform.h"

#include <numbers>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"

namespace h4 {
namespace {

TEST(RigidTransform, ComposesInMonogramOrder) {
  // X_AB: B is 1 m along x_A, rotated 90 deg about z. X_BC: C is 1 m along x_B.
  const RigidTransform X_AB(RotZ(std::numbers::pi / 2), {1, 0, 0});
  const RigidTransform X_BC(Eigen::Matrix3d::Identity(), {1, 0, 0});
  const RigidTransform X_AC = X_AB * X_BC;
  // x_B is y_A, so C sits at (1, 1, 0) in A.
  EXPECT_TRUE(X_AC.translation().isApprox(Eigen::Vector3d(1, 1, 0), 1e-12));
  EXPECT_TRUE((X_AB * Eigen::Vector3d(0, 2, 0)).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-12));
}

TEST(RigidTransform, InverseUndoes) {
  const RigidTransform X_AB = RigidTransform::FromTranslationRpy({0.1, -0.2, 0.3}, {0.4, 0.5, -0.6});
  EXPECT_TRUE((X_AB * X_AB.inverse()).IsNearlyEqualTo(RigidTransform(), 1e-12, 1e-12));
  EXPECT_TRUE((X_AB.inverse() * X_AB).matrix().isApprox(Eigen::Matrix4d::Identity(), 1e-12));
}

TEST(RigidTransform, QuaternionRoundTripAndMatrix) {
  const RigidTransform X = RigidTransform::FromTranslationRpy({1, 2, 3}, {0.1, 0.2, 0.3});
  const RigidTransform Y = RigidTransform::FromTranslationQuaternion(X.translation(), X.quaternion_wxyz());
  EXPECT_TRUE(X.IsNearlyEqualTo(Y, 1e-12, 1e-12));
  EXPECT_TRUE(X.rpy().isApprox(Eigen::Vector3d(0.1, 0.2, 0.3), 1e-12));
}

TEST(PoseError, IsRotationVectorAndTranslationDifference) {
  const RigidTransform measured = RigidTransform::FromTranslationRpy({0, 0, 1}, {0, 0, 0});
  const RigidTransform predicted = RigidTransform::FromTranslationRpy({0.001, 0, 1}, {0, 0, 0.01});
  const auto e = PoseError(measured, predicted);
  EXPECT_NEAR(e[2], 0.01, 1e-12);
  EXPECT_NEAR(e[3], 0.001, 1e-15);
  EXPECT_NEAR(e.head<2>().norm() + e.tail<2>().norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace h4

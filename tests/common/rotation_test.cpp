// Rotations against known values (not only round trips).
#include "common/geometry/rotation.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace h4 {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WrapAngle, MapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(WrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(WrapAngle(-kPi), kPi);  // -pi is outside (-pi, pi]
  EXPECT_NEAR(WrapAngle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(2 * kPi + 0.1), 0.1, 1e-12);
  EXPECT_NEAR(WrapAngle(-kPi - 0.1), kPi - 0.1, 1e-12);
  // Two readings either side of +-pi differ by a small angle.
  EXPECT_NEAR(WrapAngle((kPi - 0.01) - (-kPi + 0.02)), -0.03, 1e-12);
}

TEST(RotationFromRpy, IsRzRyRxWithKnownValues) {
  // Yaw alone: x goes to y.
  const Eigen::Matrix3d Rz = RotationFromRpy({0, 0, kPi / 2});
  EXPECT_TRUE((Rz * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  // Roll alone: y goes to z.
  const Eigen::Matrix3d Rx = RotationFromRpy({kPi / 2, 0, 0});
  EXPECT_TRUE((Rx * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  // Roll 90 then yaw 90 (fixed axes): z -> Rx -> -y -> Rz -> x.
  const Eigen::Matrix3d R = RotationFromRpy({kPi / 2, 0, kPi / 2});
  EXPECT_TRUE((R * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  // A general value written out by hand: R = Rz(c) Ry(b) Rx(a).
  const double a = 0.1, b = -0.2, c = 0.3;
  Eigen::Matrix3d expected;
  expected << std::cos(c) * std::cos(b),
      std::cos(c) * std::sin(b) * std::sin(a) - std::sin(c) * std::cos(a),
      std::cos(c) * std::sin(b) * std::cos(a) + std::sin(c) * std::sin(a),
      std::sin(c) * std::cos(b),
      std::sin(c) * std::sin(b) * std::sin(a) + std::cos(c) * std::cos(a),
      std::sin(c) * std::sin(b) * std::cos(a) - std::cos(c) * std::sin(a), -std::sin(b),
      std::cos(b) * std::sin(a), std::cos(b) * std::cos(a);
  EXPECT_TRUE(RotationFromRpy({a, b, c}).isApprox(expected, 1e-12));
}

TEST(RpyFromRotation, RecoversAnglesAndHandlesGimbalLock) {
  const Eigen::Vector3d rpy(0.3, -1.2, 2.9);
  EXPECT_TRUE(RpyFromRotation(RotationFromRpy(rpy)).isApprox(rpy, 1e-12));
  const Eigen::Matrix3d locked = RotationFromRpy({0.2, kPi / 2, 0.5});
  const Eigen::Vector3d back = RpyFromRotation(locked);
  EXPECT_NEAR(back[1], kPi / 2, 1e-9);
  EXPECT_TRUE(RotationFromRpy(back).isApprox(locked, 1e-9));
}

TEST(So3, ExpOfKnownVectorAndLogInverse) {
  // Exp of (0, 0, pi/2) is Rz(pi/2).
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_TRUE(So3Exp({0, 0, kPi / 2}).isApprox(expected, 1e-12));
  // Log of Rx(0.7) is (0.7, 0, 0).
  EXPECT_TRUE(So3Log(RotationFromRpy({0.7, 0, 0})).isApprox(Eigen::Vector3d(0.7, 0, 0), 1e-12));
  // Near pi and near zero.
  const Eigen::Vector3d w_big = Eigen::Vector3d(1, 2, -2).normalized() * (kPi - 1e-7);
  EXPECT_TRUE(So3Log(So3Exp(w_big)).isApprox(w_big, 1e-6));
  const Eigen::Vector3d w_small(1e-10, -2e-10, 3e-10);
  EXPECT_TRUE(So3Log(So3Exp(w_small)).isApprox(w_small, 1e-6));
}

TEST(Quaternion, KnownValuesAndUnitNormCheck) {
  Eigen::Matrix3d R;
  // 90 deg about z: q = (cos 45, 0, 0, sin 45).
  const double c = std::sqrt(0.5);
  ASSERT_TRUE(RotationFromQuaternion(c, 0, 0, c, &R));
  EXPECT_TRUE(R.isApprox(RotZ(kPi / 2), 1e-12));
  EXPECT_FALSE(RotationFromQuaternion(1.01, 0, 0, 0, &R));
  EXPECT_FALSE(RotationFromQuaternion(std::nan(""), 0, 0, 0, &R));
  // Negated quaternion is the same rotation; canonical output has w >= 0.
  ASSERT_TRUE(RotationFromQuaternion(-c, 0, 0, -c, &R));
  const Eigen::Vector4d q = QuaternionWxyzFromRotation(R);
  EXPECT_TRUE(q.isApprox(Eigen::Vector4d(c, 0, 0, c), 1e-12));
}

}  // namespace
}  // namespace h4

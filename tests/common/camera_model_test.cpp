// Tests for common/camera/camera_model: OpenCV's distortion model by known values, its
// Jacobians against finite differences, and undistortion inverting it. (Agreement with
// cv::projectPoints itself is checked in tests/firmware, which links OpenCV.)
#include "common/camera/camera_model.h"

#include <gtest/gtest.h>

namespace h4 {
namespace {

CameraIntrinsics Camera(int distortion_count) {
  CameraIntrinsics c;
  c.width = 1024;
  c.height = 768;
  c.K << 800.0, 0.0, 512.0, 0.0, 810.0, 384.0, 0.0, 0.0, 1.0;
  c.distortion = Eigen::VectorXd::Zero(distortion_count);
  const double all[8] = {-0.2, 0.05, 0.001, -0.002, 0.01, 0.02, -0.01, 0.005};
  for (int i = 0; i < distortion_count; ++i) c.distortion[i] = all[i];
  return c;
}

TEST(CameraModelTest, PinholeWithoutDistortionProjectsByHand) {
  const CameraModel camera(Camera(0));
  Eigen::Vector2d uv;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0.1, -0.05, 0.5), &uv));
  EXPECT_NEAR(uv.x(), 512.0 + 800.0 * 0.2, 1e-12);
  EXPECT_NEAR(uv.y(), 384.0 - 810.0 * 0.1, 1e-12);
}

TEST(CameraModelTest, RadialAndTangentialTermsMatchOpenCvFormula) {
  const CameraModel camera(Camera(5));
  const double x = 0.3, y = -0.2, r2 = x * x + y * y;
  const double g = 1 - 0.2 * r2 + 0.05 * r2 * r2 + 0.01 * r2 * r2 * r2;
  const double xd = x * g + 2 * 0.001 * x * y + (-0.002) * (r2 + 2 * x * x);
  const double yd = y * g + 0.001 * (r2 + 2 * y * y) + 2 * (-0.002) * x * y;
  const Eigen::Vector2d uv = camera.PixelFromNormalized(Eigen::Vector2d(x, y));
  EXPECT_NEAR(uv.x(), 800.0 * xd + 512.0, 1e-10);
  EXPECT_NEAR(uv.y(), 810.0 * yd + 384.0, 1e-10);
}

TEST(CameraModelTest, RationalModelDividesByDenominator) {
  const CameraModel camera(Camera(8));
  const double x = 0.25, y = 0.1, r2 = x * x + y * y;
  const double g = (1 - 0.2 * r2 + 0.05 * r2 * r2 + 0.01 * r2 * r2 * r2) /
                   (1 + 0.02 * r2 - 0.01 * r2 * r2 + 0.005 * r2 * r2 * r2);
  const Eigen::Vector2d xd = camera.Distort(Eigen::Vector2d(x, y));
  EXPECT_NEAR(xd.x(), x * g + 2 * 0.001 * x * y - 0.002 * (r2 + 2 * x * x), 1e-14);
  EXPECT_NEAR(xd.y(), y * g + 0.001 * (r2 + 2 * y * y) - 2 * 0.002 * x * y, 1e-14);
}

TEST(CameraModelTest, ProjectionJacobianMatchesFiniteDifferences) {
  for (int n : {4, 5, 8}) {
    const CameraModel camera(Camera(n));
    const Eigen::Vector3d p(0.12, -0.08, 0.55);
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J;
    ASSERT_TRUE(camera.Project(p, &uv, &J));
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-7;
      Eigen::Vector2d up, um;
      camera.Project(p + h * Eigen::Vector3d::Unit(k), &up);
      camera.Project(p - h * Eigen::Vector3d::Unit(k), &um);
      const Eigen::Vector2d numeric = (up - um) / (2 * h);
      EXPECT_NEAR((J.col(k) - numeric).norm(), 0.0, 1e-5 * (1 + numeric.norm())) << n << " " << k;
    }
  }
}

TEST(CameraModelTest, UndistortionInvertsDistortionAcrossTheImage) {
  const CameraModel camera(Camera(8));
  for (double u = 0; u <= 1023; u += 170.5) {
    for (double v = 0; v <= 767; v += 127.75) {
      Eigen::Vector2d xn;
      ASSERT_TRUE(camera.NormalizedFromPixel(Eigen::Vector2d(u, v), &xn));
      const Eigen::Vector2d back = camera.PixelFromNormalized(xn);
      EXPECT_NEAR((back - Eigen::Vector2d(u, v)).norm(), 0.0, 1e-8);
    }
  }
}

TEST(CameraModelTest, PointBehindCameraIsRefused) {
  const CameraModel camera(Camera(5));
  Eigen::Vector2d uv(-1, -1);
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0.1, 0.1, -0.5), &uv));
  EXPECT_EQ(uv, Eigen::Vector2d(-1, -1));
}

TEST(CameraModelTest, UnsupportedDistortionCountIsInvalid) {
  EXPECT_FALSE(CameraModel(Camera(6)).valid());
  EXPECT_TRUE(CameraModel(Camera(5)).valid());
}

}  // namespace
}  // namespace h4

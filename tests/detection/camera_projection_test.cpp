// common/camera/camera_model against OpenCV's own cv::projectPoints (the model the
// camera YAML files are calibrated with), for 4, 5 and 8 distortion coefficients, and
// against cv::fisheye (projection and undistortion) for the equidistant model.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "common/camera/camera_model.h"
#include "common/units.h"

namespace h4 {
namespace {

TEST(CameraProjectionTest, MatchesCvProjectPoints) {
  const double all[8] = {-0.25, 0.09, 0.0012, -0.0008, -0.02, 0.03, -0.01, 0.004};
  for (int n : {4, 5, 8}) {
    CameraIntrinsics intrinsics = CameraIntrinsics::Pinhole(1024, 768, 817.0, 816.2, 515.3, 380.7);
    intrinsics.distortion = Eigen::VectorXd(n);
    for (int i = 0; i < n; ++i) intrinsics.distortion[i] = all[i];
    const CameraModel camera(intrinsics);

    std::vector<cv::Point3d> points;
    for (double x = -0.25; x <= 0.25; x += 0.05) {
      for (double y = -0.2; y <= 0.2; y += 0.05) points.emplace_back(x, y, 0.5 + 0.3 * x);
    }
    cv::Mat K(3, 3, CV_64F), D(1, n, CV_64F);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) K.at<double>(r, c) = intrinsics.K(r, c);
    for (int i = 0; i < n; ++i) D.at<double>(0, i) = all[i];
    std::vector<cv::Point2d> expected;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, expected);
    for (size_t i = 0; i < points.size(); ++i) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(camera.Project(Eigen::Vector3d(points[i].x, points[i].y, points[i].z), &uv));
      EXPECT_NEAR(uv.x(), expected[i].x, 1e-9) << n;
      EXPECT_NEAR(uv.y(), expected[i].y, 1e-9) << n;
    }
  }
}

CameraIntrinsics WideFisheye() {
  CameraIntrinsics intrinsics = CameraIntrinsics::Pinhole(1280, 960, 340.0, 339.2, 641.5, 478.9);
  intrinsics.distortion_model = DistortionModel::kEquidistant;
  intrinsics.distortion = Eigen::Vector4d(0.031, -0.012, 0.0041, -0.0007);
  return intrinsics;
}

// Rays from the axis to 85 degrees off it, all around.
std::vector<cv::Point3d> WideRays() {
  std::vector<cv::Point3d> points;
  for (double angle_deg = 0; angle_deg <= 85; angle_deg += 5) {
    for (double azimuth = 0.1; azimuth < 2 * M_PI; azimuth += 0.7) {
      const double theta = RadiansFromDegrees(angle_deg);
      points.emplace_back(std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth),
                          std::cos(theta));
    }
  }
  return points;
}

cv::Mat CvMatrix(const Eigen::Matrix3d& K) {
  cv::Mat out(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out.at<double>(r, c) = K(r, c);
  return out;
}

TEST(CameraProjectionTest, EquidistantMatchesCvFisheyeProjectPoints) {
  const CameraIntrinsics intrinsics = WideFisheye();
  const CameraModel camera(intrinsics);
  const std::vector<cv::Point3d> points = WideRays();
  const cv::Vec4d D(0.031, -0.012, 0.0041, -0.0007);
  std::vector<cv::Point2d> expected;
  cv::fisheye::projectPoints(points, expected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                             CvMatrix(intrinsics.K), D);
  for (size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(Eigen::Vector3d(points[i].x, points[i].y, points[i].z), &uv));
    EXPECT_NEAR(uv.x(), expected[i].x, 1e-8) << i;
    EXPECT_NEAR(uv.y(), expected[i].y, 1e-8) << i;
  }
}

// cv::fisheye::undistortPoints gives normalised coordinates too (no R, no P); OpenCV
// stops at a fixed iteration count, hence the looser tolerance (a few 1e-9 at 85 deg).
TEST(CameraProjectionTest, EquidistantUndistortionAgreesWithCvFisheyeUndistortPoints) {
  const CameraIntrinsics intrinsics = WideFisheye();
  const CameraModel camera(intrinsics);
  std::vector<cv::Point2d> pixels;
  for (const cv::Point3d& p : WideRays()) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(Eigen::Vector3d(p.x, p.y, p.z), &uv));
    pixels.emplace_back(uv.x(), uv.y());
  }
  std::vector<cv::Point2d> expected;
  cv::fisheye::undistortPoints(pixels, expected, CvMatrix(intrinsics.K),
                               cv::Vec4d(0.031, -0.012, 0.0041, -0.0007));
  for (size_t i = 0; i < pixels.size(); ++i) {
    Eigen::Vector2d xn;
    ASSERT_TRUE(camera.NormalizedFromPixel(Eigen::Vector2d(pixels[i].x, pixels[i].y), &xn));
    const Eigen::Vector2d cv_xn(expected[i].x, expected[i].y);
    // Compare as angles: near 90 degrees the normalised coordinates grow without bound.
    EXPECT_NEAR(std::atan(xn.norm()), std::atan(cv_xn.norm()), 1e-6) << i;
    if (xn.norm() > 1e-6) {
      EXPECT_NEAR((xn.normalized() - cv_xn.normalized()).norm(), 0.0, 1e-6) << i;
    }
  }
}

}  // namespace
}  // namespace h4

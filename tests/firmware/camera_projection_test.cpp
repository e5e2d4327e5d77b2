// common/camera/camera_model against OpenCV's own cv::projectPoints (the model the
// camera YAML files are calibrated with), for 4, 5 and 8 distortion coefficients.
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "common/camera/camera_model.h"

namespace h4 {
namespace {

TEST(CameraProjectionTest, MatchesCvProjectPoints) {
  const double all[8] = {-0.25, 0.09, 0.0012, -0.0008, -0.02, 0.03, -0.01, 0.004};
  for (int n : {4, 5, 8}) {
    CameraIntrinsics intrinsics;
    intrinsics.width = 1024;
    intrinsics.height = 768;
    intrinsics.K << 817.0, 0.0, 515.3, 0.0, 816.2, 380.7, 0.0, 0.0, 1.0;
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

}  // namespace
}  // namespace h4

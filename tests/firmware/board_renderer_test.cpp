// Tests for firmware/render: area sampling, reproducibility, and geometry (a rendered
// corner lands where the camera model projects it, checked through detection).
#include "firmware/render/board_renderer.h"

#include <gtest/gtest.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "firmware/detection/board_detector.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

// A camera without distortion, 1 px per mm at 1 m.
CameraIntrinsics UnitCamera() {
  CameraIntrinsics camera;
  camera.width = 320;
  camera.height = 240;
  camera.K << 1000.0, 0.0, 160.0, 0.0, 1000.0, 120.0, 0.0, 0.0, 1.0;
  camera.distortion = Eigen::VectorXd::Zero(5);
  return camera;
}

TEST(BoardRendererTest, PixelHalfCoveredByAnEdgeIsMidGrey) {
  AprilGridSpec board;
  board.cols = 1;
  board.rows = 1;
  board.tag_size = 0.08;  // 80 px tag, 10 px cells
  RenderOptions options;
  options.blur_sigma_px = 0;
  options.noise_sigma = 0;
  const BoardRenderer renderer(board, UnitCamera(), options);
  ASSERT_TRUE(renderer.ok()) << renderer.error();
  // Tag's left edge (x = 0 in T) at u = 100.0, a pixel centre; top edge at v = 80.25.
  const RigidTransform X_CT(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.06, -0.03975, 1.0));
  const cv::Mat image = renderer.RenderClean(X_CT);
  const float mid = static_cast<float>(0.5 * (options.black_level + options.white_level));
  EXPECT_NEAR(image.at<float>(120, 100), mid, 0.5);
  EXPECT_NEAR(image.at<float>(120, 99), options.white_level, 1e-3);
  EXPECT_NEAR(image.at<float>(120, 101), options.black_level, 1e-3);
  // Pixel row 80 spans v in [79.5, 80.5]: three quarters white (above the tag), a
  // quarter black.
  const double expected = 0.75 * options.white_level + 0.25 * options.black_level;
  EXPECT_NEAR(image.at<float>(80, 130), expected, 0.5);
}

TEST(BoardRendererTest, SameSeedGivesSameFramesAndNoiseHasRequestedSigma) {
  const BoardRenderer renderer(scenes::PaperBoard(), scenes::PaperCamera(), RenderOptions{});
  ASSERT_TRUE(renderer.ok());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.2, 0.3, 0.1);
  const cv::Mat a = renderer.Render(X_CT, 7), b = renderer.Render(X_CT, 7);
  const cv::Mat c = renderer.Render(X_CT, 8);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  cv::Mat diff;
  cv::subtract(a, c, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(diff, mean, stddev);
  // Difference of two independent noises of sigma 2 (plus rounding): sigma ~ 2.8.
  EXPECT_NEAR(stddev[0], 2.0 * std::sqrt(2.0), 0.15);
}

TEST(BoardRendererTest, RenderedCornersLandWhereTheCameraModelProjects) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  RenderOptions options;
  options.noise_sigma = 0;  // geometry only
  const BoardRenderer renderer(board, camera, options);
  const BoardDetector detector(board, camera);
  const CameraModel model(camera);
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.35, 1.0, 0.4, 0.02, -0.01);
  const BoardDetection detection = detector.Detect(renderer.RenderClean(X_CT));
  ASSERT_EQ(detection.corners.size(), 144u);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(model.Project(X_CT * c.p_TQ, &uv));
    mean += (c.uv - uv) / 144.0;
    EXPECT_LT((c.uv - uv).norm(), 0.02) << "corner " << c.id;
  }
  EXPECT_LT(mean.norm(), 0.002);  // no systematic shift between renderer and model
}

}  // namespace
}  // namespace h4::cam

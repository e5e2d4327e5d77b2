// libapriltag's pixel convention: measured on rendered images with known truth, and
// corrected at the boundary (firmware/detection/apriltag_detector.h).
#include "firmware/detection/apriltag_detector.h"

#include <gtest/gtest.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

TEST(AprilTagDetectorTest, CornersAreInOpenCvPixelConventionAfterCorrection) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, RenderOptions{});
  const BoardModel model(board);
  const CameraModel projection(camera);
  const AprilTagDetector detector;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  int n = 0;
  for (const RigidTransform& X_CT : scenes::RandomPoses(3, 11)) {
    const cv::Mat image = renderer.Render(X_CT, 3);
    for (const TagDetection& tag : detector.Detect(image)) {
      for (int k = 0; k < 4; ++k) {
        const int id = model.TagCornerId(tag.id, k);
        ASSERT_GE(id, 0);
        Eigen::Vector2d uv;
        ASSERT_TRUE(projection.Project(X_CT * model.corners()[static_cast<size_t>(id)], &uv));
        const Eigen::Vector2d error = tag.corners_px[static_cast<size_t>(k)] - uv;
        EXPECT_LT(error.norm(), 0.3) << "tag " << tag.id << " corner " << k;
        mean += error;
        ++n;
      }
    }
  }
  ASSERT_GT(n, 300);
  mean /= n;
  // Uncorrected, libapriltag's corners sit at +0.5 px on both axes.
  EXPECT_LT(std::abs(mean.x()), 0.02);
  EXPECT_LT(std::abs(mean.y()), 0.02);
  EXPECT_EQ(AprilTagDetector::kCornerOffsetPx, -0.5);
}

TEST(AprilTagDetectorTest, FindsEveryTagOfTheBoardById) {
  const AprilGridSpec board = scenes::PaperBoard();
  const BoardRenderer renderer(board, scenes::PaperCamera(), RenderOptions{});
  const AprilTagDetector detector;
  const auto tags =
      detector.Detect(renderer.Render(scenes::BoardPose(board, 0.6, 0.4, 2.0, 0.5), 1));
  std::vector<int> ids;
  for (const TagDetection& tag : tags) ids.push_back(tag.id);
  std::sort(ids.begin(), ids.end());
  ASSERT_EQ(ids.size(), 36u);
  for (int i = 0; i < 36; ++i) EXPECT_EQ(ids[static_cast<size_t>(i)], i);
}

TEST(AprilTagDetectorTest, UnknownFamilyIsAnError) {
  AprilTagOptions options;
  options.family = "tag99h1";
  const AprilTagDetector detector(options);
  EXPECT_FALSE(detector.ok());
  EXPECT_NE(detector.error().find("tag99h1"), std::string::npos);
}

}  // namespace
}  // namespace h4::cam

// libapriltag's pixel convention: measured on rendered images with known truth, and
// corrected at the boundary (firmware/detection/apriltag_detector.h); the families widened
// for Kalibr's 2-cell border (tag_family.h), and the second, opened search leaving the
// caller's image alone.
#include "firmware/detection/apriltag_detector.h"

#include <apriltag/apriltag.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/formats/board_yaml.h"
#include "firmware/render/paper_scenes.h"
#include "tests/render/paper_scene_helpers.h"

namespace h4::cam {
namespace {

TEST(AprilTagDetectorTest, CornersAreInOpenCvPixelConventionAfterCorrection) {
  const PaperScene scene;
  const AprilTagDetector detector;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  int n = 0;
  for (const RigidTransform& X_CT : scenes::RandomPoses(3, 11)) {
    const cv::Mat image = scene.renderer.Render(X_CT, 3);
    for (const TagDetection& tag : detector.Detect(image)) {
      for (int k = 0; k < 4; ++k) {
        const int id = scene.board_model.TagCornerId(tag.id, k);
        ASSERT_GE(id, 0);
        Eigen::Vector2d uv;
        ASSERT_TRUE(scene.projection.Project(
            X_CT * scene.board_model.corners()[static_cast<size_t>(id)], &uv));
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

// The board reader (common) refuses families and ids h4cam cannot detect from its own
// table; it must be libapriltag's.
TEST(AprilTagDetectorTest, TheBoardReadersFamiliesAreThoseH4camCreatesWithTheirCodes) {
  for (const AprilTagFamilyInfo& family : AprilTagFamilies()) {
    const TagFamilyPtr created = CreateTagFamily(family.name);
    ASSERT_NE(created, nullptr) << family.name;
    EXPECT_EQ(static_cast<int>(created->ncodes), family.codes) << family.name;
  }
}

TEST(AprilTagDetectorTest, WideBorderFamilyMovesEveryBitOneCellIn) {
  const TagFamilyPtr plain = CreateTagFamily("tag36h11");
  const TagFamilyPtr wide = CreateTagFamily("tag36h11", 2);
  ASSERT_TRUE(plain && wide);
  EXPECT_EQ(wide->width_at_border, plain->width_at_border + 2);
  EXPECT_EQ(wide->total_width, plain->total_width + 2);
  ASSERT_EQ(wide->nbits, plain->nbits);
  for (uint32_t i = 0; i < plain->nbits; ++i) {
    EXPECT_EQ(wide->bit_x[i], plain->bit_x[i] + 1);
    EXPECT_EQ(wide->bit_y[i], plain->bit_y[i] + 1);
  }
  EXPECT_EQ(CreateTagFamily("tag36h11", 0), nullptr);
  EXPECT_EQ(CreateTagFamily("tag36h11", kMaxBorderCells + 1), nullptr);
}

TEST(AprilTagDetectorTest, TwoCellBorderCellsWrapTheSameDataInBlack) {
  const TagFamilyPtr family = CreateTagFamily("tag36h11");
  int narrow = 0, wide = 0;
  const std::vector<bool> one = TagCells(*family, 7, 1, &narrow);
  const std::vector<bool> two = TagCells(*family, 7, 2, &wide);
  ASSERT_EQ(narrow, 8);
  ASSERT_EQ(wide, 10);
  for (int y = 0; y < wide; ++y) {
    for (int x = 0; x < wide; ++x) {
      const bool white = two[static_cast<size_t>(y * wide + x)];
      if (x < 2 || y < 2 || x >= 8 || y >= 8) {
        EXPECT_FALSE(white) << x << ", " << y;  // the 2-cell black border
      } else {
        EXPECT_EQ(white, one[static_cast<size_t>((y - 1) * narrow + x - 1)]) << x << ", " << y;
      }
    }
  }
}

TEST(AprilTagDetectorTest, OpenedSearchLeavesTheCallersImageAlone) {
  AprilTagOptions options;
  options.border_cells = 2;
  options.open_contacts_px = 1;
  const AprilTagDetector detector(options);
  ASSERT_TRUE(detector.ok()) << detector.error();
  cv::Mat image(120, 160, CV_8UC1, cv::Scalar(200));
  cv::rectangle(image, cv::Rect(40, 30, 60, 60), cv::Scalar(20), cv::FILLED);
  const cv::Mat before = image.clone();
  detector.Detect(image);
  detector.DetectCandidates(image);
  EXPECT_EQ(cv::countNonZero(image != before), 0);
}

}  // namespace
}  // namespace h4::cam

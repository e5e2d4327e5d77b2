// The committed files the simulated camera runs with (boards/sim_camera_1024x768.yaml and
// boards/aprilgrid_6x6_30mm.yaml) must describe the scene the firmware's tests use
// (firmware/render/paper_scenes.h), so that the demo measures what the tests check.
#include <gtest/gtest.h>
#include <opencv2/core/persistence.hpp>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

const std::string kBoardsFolder = std::string(H4_SOURCE_DIR) + "/boards/";

TEST(SimCameraFileTest, MatchesThePaperCameraOfTheTests) {
  const CameraIntrinsics file = ReadCameraYaml(kBoardsFolder + "sim_camera_1024x768.yaml");
  const CameraIntrinsics paper = scenes::PaperCamera();
  EXPECT_EQ(file.width, paper.width);
  EXPECT_EQ(file.height, paper.height);
  EXPECT_TRUE(file.K.isApprox(paper.K, 1e-12)) << file.K;
  ASSERT_EQ(file.distortion.size(), paper.distortion.size());
  EXPECT_TRUE(file.distortion.isApprox(paper.distortion, 1e-12));
}

TEST(SimCameraFileTest, OpenCvReadsIt) {
  cv::FileStorage fs(kBoardsFolder + "sim_camera_1024x768.yaml", cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  cv::Mat K;
  fs["camera_matrix"] >> K;
  ASSERT_EQ(K.rows, 3);
  EXPECT_DOUBLE_EQ(K.at<double>(0, 0), 817.0);
}

// The printed board has 7.5 mm gaps (tagSpacing 0.25), the tests' scene 9 mm (0.3): the same
// 6 x 6 grid of 30 mm tags otherwise, so the tests' accuracy figures carry over.
TEST(SimCameraFileTest, TheBoardFileIsThePaperBoardsGrid) {
  const BoardSpec file = ReadBoardYaml(kBoardsFolder + "aprilgrid_6x6_30mm.yaml");
  const AprilGridSpec* grid = std::get_if<AprilGridSpec>(&file);
  ASSERT_NE(grid, nullptr);
  const AprilGridSpec paper = scenes::PaperBoard();
  EXPECT_EQ(grid->cols, paper.cols);
  EXPECT_EQ(grid->rows, paper.rows);
  EXPECT_DOUBLE_EQ(grid->tag_size, paper.tag_size);
  EXPECT_DOUBLE_EQ(grid->tag_spacing, 0.25);
  EXPECT_EQ(grid->tag_family, paper.tag_family);
  EXPECT_EQ(grid->layout, paper.layout);
}

}  // namespace
}  // namespace h4::cam

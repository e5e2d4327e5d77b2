// `h4cam measure` end to end on rendered image files: one row per group, the pose of a
// group with the board, empty pose fields for a group without.
#include "firmware/cli/measure_command.h"

#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/formats/board_poses_csv.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "firmware/render/board_renderer.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {
namespace fs = std::filesystem;

TEST(MeasureCommandTest, WritesOneRowPerGroupWithEmptyPoseWhenNoBoard) {
  const fs::path dir = fs::path(H4_BINARY_DIR) / "test_tmp" / "measure_command";
  fs::remove_all(dir);
  fs::create_directories(dir / "images");
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  WriteBoardYaml((dir / "board.yaml").string(), board);
  WriteCameraYaml((dir / "camera.yaml").string(), camera);
  const BoardRenderer renderer(board, camera, RenderOptions{});
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.3, 1.2, 0.4);
  const cv::Mat clean = renderer.RenderClean(X_CT);
  cv::RNG rng(1);
  for (int k = 0; k < 4; ++k) {  // group 1: the board; group 2: an empty scene
    const cv::Mat frame =
        k < 2 ? renderer.Expose(clean, rng) : cv::Mat(768, 1024, CV_8U, cv::Scalar(90));
    cv::imwrite((dir / "images" / ("f" + std::to_string(k) + ".png")).string(), frame);
  }
  MeasureArgs args;
  args.board_path = (dir / "board.yaml").string();
  args.camera_path = (dir / "camera.yaml").string();
  args.images = {(dir / "images").string()};
  args.group = 2;
  args.out_path = (dir / "poses.csv").string();
  std::ostringstream progress;
  EXPECT_EQ(RunMeasure(args, progress), 1);
  EXPECT_NE(progress.str().find("[2/2]"), std::string::npos);

  const std::vector<BoardPoseRow> rows = ReadBoardPosesCsv(args.out_path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(fs::path(rows[0].image).filename(), "f0.png");
  ASSERT_TRUE(rows[0].X_CT.has_value());
  EXPECT_TRUE(rows[0].X_CT->IsNearlyEqualTo(X_CT, 1e-4, 1e-3));
  EXPECT_EQ(rows[0].corners, 144);
  EXPECT_EQ(fs::path(rows[1].image).filename(), "f2.png");
  EXPECT_FALSE(rows[1].X_CT.has_value());
}

TEST(MeasureCommandTest, ImageOfWrongSizeIsAnErrorNamingTheFile) {
  const fs::path dir = fs::path(H4_BINARY_DIR) / "test_tmp" / "measure_command_size";
  fs::remove_all(dir);
  fs::create_directories(dir);
  WriteBoardYaml((dir / "board.yaml").string(), scenes::PaperBoard());
  WriteCameraYaml((dir / "camera.yaml").string(), scenes::PaperCamera());
  cv::imwrite((dir / "small.png").string(), cv::Mat(10, 10, CV_8U, cv::Scalar(0)));
  MeasureArgs args;
  args.board_path = (dir / "board.yaml").string();
  args.camera_path = (dir / "camera.yaml").string();
  args.images = {(dir / "small.png").string()};
  args.out_path = (dir / "poses.csv").string();
  std::ostringstream progress;
  try {
    RunMeasure(args, progress);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("small.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace h4::cam

// `h4cam measure` end to end on rendered image files: one row per group, the pose of a
// group with the board, empty pose fields for a group without.
#include "firmware/cli/measure_command.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/formats/board_poses_csv.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "firmware/render/board_renderer.h"
#include "firmware/render/paper_scenes.h"
#include "tests/support/test_dir.h"

namespace h4::cam {
namespace {
namespace fs = std::filesystem;

// A fresh directory for the running test under test_tmp in the build tree, holding the
// paper's board.yaml and camera.yaml.
fs::path FreshDirWithPaperBoardAndCamera() {
  const fs::path dir = FreshTestDir("measure_command_", fs::path(H4_BINARY_DIR) / "test_tmp");
  WriteBoardYaml((dir / "board.yaml").string(), scenes::PaperBoard());
  WriteCameraYaml((dir / "camera.yaml").string(), scenes::PaperCamera());
  return dir;
}

// MeasureArgs reading the board and camera of `dir` and writing its poses.csv (no images yet).
MeasureArgs ArgsReadingAndWritingIn(const fs::path& dir) {
  MeasureArgs args;
  args.board_path = (dir / "board.yaml").string();
  args.camera_path = (dir / "camera.yaml").string();
  args.out_path = (dir / "poses.csv").string();
  return args;
}

// Writes f0.png to f3.png into `images` (created): two groups of two frames, the paper's board
// at one pose (exposed with noise seed `seed`) in group `board_group` (1 or 2), an empty scene
// in the other. Returns the board's pose.
RigidTransform WriteTwoGroupsOfTwoFrames(const fs::path& images, int board_group, int seed) {
  fs::create_directories(images);
  const AprilGridSpec board = scenes::PaperBoard();
  const BoardRenderer renderer(board, scenes::PaperCamera(), RenderOptions{});
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.3, 1.2, 0.4);
  const cv::Mat clean = renderer.RenderClean(X_CT);
  cv::RNG rng(seed);
  for (int k = 0; k < 4; ++k) {
    const bool board_in_view = (k / 2 + 1) == board_group;
    const cv::Mat frame =
        board_in_view ? renderer.Expose(clean, rng) : cv::Mat(768, 1024, CV_8U, cv::Scalar(90));
    cv::imwrite((images / fmt::format("f{}.png", k)).string(), frame);
  }
  return X_CT;
}

TEST(MeasureCommandTest, WritesOneRowPerGroupWithEmptyPoseWhenNoBoard) {
  const fs::path dir = FreshDirWithPaperBoardAndCamera();
  const RigidTransform X_CT =
      WriteTwoGroupsOfTwoFrames(dir / "images", /*board_group=*/1, /*seed=*/1);
  MeasureArgs args = ArgsReadingAndWritingIn(dir);
  args.images = {(dir / "images").string()};
  args.group = 2;
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

// --corners-out: the corners of the pose of row 1 (the first group shows no board), with the
// board's tag and corner ids, and the reported pose reprojects them within a fraction of a
// pixel (common/formats/README.md#board-corners-csv).
TEST(MeasureCommandTest, CornersOutCarriesTheCornersOfEachPose) {
  const fs::path dir = FreshDirWithPaperBoardAndCamera();
  WriteTwoGroupsOfTwoFrames(dir / "images", /*board_group=*/2, /*seed=*/2);
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  MeasureArgs args = ArgsReadingAndWritingIn(dir);
  args.images = {(dir / "images").string()};
  args.group = 2;
  args.corners_out_path = (dir / "corners.csv").string();
  std::ostringstream progress;
  ASSERT_EQ(RunMeasure(args, progress), 1);

  const std::vector<BoardPoseRow> rows = ReadBoardPosesCsv(args.out_path);
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_TRUE(rows[1].X_CT.has_value());
  const std::vector<h4::CornerObservation> corners = ReadCornersCsv(args.corners_out_path);
  ASSERT_EQ(static_cast<int>(corners.size()), rows[1].corners);
  const BoardModel model(board);
  const CameraModel projection(camera);
  double worst_px = 0;
  for (const h4::CornerObservation& c : corners) {
    EXPECT_EQ(c.pose_id, 1);
    EXPECT_EQ(c.tag_id, board.first_id + c.corner / 4);
    ASSERT_TRUE(c.sigma_px.has_value());
    EXPECT_GT(*c.sigma_px, 0.0);
    EXPECT_LT(*c.sigma_px, 0.5);
    const std::optional<Eigen::Vector3d> p_TQ = model.Corner(c.corner);
    ASSERT_TRUE(p_TQ.has_value()) << c.corner;
    Eigen::Vector2d uv;
    ASSERT_TRUE(projection.Project(*rows[1].X_CT * *p_TQ, &uv));
    worst_px = std::max(worst_px, (uv - Eigen::Vector2d(c.u, c.v)).norm());
  }
  EXPECT_LT(worst_px, 0.3);
}

TEST(MeasureCommandTest, CornersOutThatIsTheOutFileIsRefused) {
  MeasureArgs args;
  args.board_path = "board.yaml";
  args.camera_path = "camera.yaml";
  args.out_path = (fs::path(H4_BINARY_DIR) / "test_tmp" / "same.csv").string();
  args.corners_out_path = args.out_path;
  std::ostringstream progress;
  EXPECT_THROW(RunMeasure(args, progress), std::invalid_argument);
}

TEST(MeasureCommandTest, ImageOfWrongSizeIsAnErrorNamingTheFile) {
  const fs::path dir = FreshDirWithPaperBoardAndCamera();
  cv::imwrite((dir / "small.png").string(), cv::Mat(10, 10, CV_8U, cv::Scalar(0)));
  MeasureArgs args = ArgsReadingAndWritingIn(dir);
  args.images = {(dir / "small.png").string()};
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

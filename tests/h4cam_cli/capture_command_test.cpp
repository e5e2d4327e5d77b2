// `h4cam capture` / `h4cam preview` (firmware/cli/capture_command.h) on the sim source: the
// frames saved, and the figures printed per frame move the way a technician reads them
// (the board found whole, a sub-pixel RMS, coverage larger when the board is nearer, pixels
// saturating when the light is too strong).
#include "firmware/cli/capture_command.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace h4::cam {
namespace {

namespace fs = std::filesystem;

/// The numbers after `label` in every frame line of `output` ("coverage 9.8 %" -> 9.8).
std::vector<double> Figures(const std::string& output, const std::string& label) {
  std::vector<double> values;
  const std::regex pattern(label + " ([0-9.]+)");
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (line.rfind("frame ", 0) == 0 && std::regex_search(line, match, pattern)) {
      values.push_back(std::stod(match[1]));
    }
  }
  return values;
}

class CaptureCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(H4_BINARY_DIR) / "test_tmp" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    args_.source = "sim";
    args_.board_path = H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml";
    args_.camera_path = H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml";
    args_.out_dir = dir_.string();
  }
  /// Runs capture (save_frames) or preview; the printed output.
  std::string Run(bool save_frames, CaptureSummary* summary = nullptr) {
    std::ostringstream out;
    const std::atomic<bool> stop{false};
    const CaptureSummary s = RunCapture(args_, save_frames, out, stop);
    if (summary != nullptr) *summary = s;
    return out.str();
  }
  fs::path dir_;
  CaptureArgs args_;
};

// issue 27 point 15: an unreadable last file of `--source dir:` was skipped silently
// ("checked 1 frame(s)", exit 0) while the same file anywhere else was an error.
TEST_F(CaptureCommandTest, AnUnreadableLastFileOfADirectoryIsAnError) {
  const fs::path images = dir_ / "images";
  fs::create_directories(images);
  ASSERT_TRUE(
      cv::imwrite((images / "a.png").string(), cv::Mat(768, 1024, CV_8UC1, cv::Scalar(128))));
  std::ofstream(images / "b.png") << "not a png";
  args_.source = "dir:" + images.string();
  args_.out_dir.clear();
  try {
    Run(false);
    FAIL() << "the unreadable b.png was skipped";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("b.png"), std::string::npos) << e.what();
  }
}

TEST_F(CaptureCommandTest, SavesTheFramesAndPrintsTheDetectionOfEach) {
  args_.count = 2;
  args_.draw = true;
  CaptureSummary summary;
  const std::string output = Run(/*save_frames=*/true, &summary);
  EXPECT_EQ(summary.frames, 2);
  EXPECT_EQ(summary.with_board, 2);
  for (const char* name : {"frame_0000.png", "frame_0001.png"}) {
    const cv::Mat frame = cv::imread((dir_ / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(frame.empty()) << name;
    EXPECT_EQ(frame.cols, 1024);
    EXPECT_EQ(frame.rows, 768);
    EXPECT_EQ(frame.type(), CV_8UC1) << "saved as the camera gave it, for calibrate-intrinsics";
  }
  const cv::Mat overlay = cv::imread((dir_ / "overlay_0000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(overlay.empty());
  EXPECT_EQ(overlay.type(), CV_8UC3);
  EXPECT_NE(output.find("frame 0: board ok, 36/36 tags, 144/144 corners"), std::string::npos)
      << output;
  const std::vector<double> rms = Figures(output, "rms");
  ASSERT_EQ(rms.size(), 2u) << output;
  for (double r : rms) EXPECT_LT(r, 0.3) << output;
  for (double sharpness : Figures(output, "sharpness")) EXPECT_GT(sharpness, 0.0) << output;
  EXPECT_NE(output.find("captured 2 frame(s), 2 showing the board"), std::string::npos) << output;
}

TEST_F(CaptureCommandTest, CoverageGrowsWhenTheBoardIsNearer) {
  args_.count = 1;
  args_.sim_pose = {-0.1, -0.1, 0.7, 1, 0, 0, 0};
  const std::vector<double> far = Figures(Run(/*save_frames=*/false), "coverage");
  args_.sim_pose = {-0.1, -0.1, 0.4, 1, 0, 0, 0};
  const std::vector<double> near = Figures(Run(/*save_frames=*/false), "coverage");
  ASSERT_EQ(far.size(), 1u);
  ASSERT_EQ(near.size(), 1u);
  // The board's image area goes with 1 / depth^2: (0.7 / 0.4)^2 = 3.1.
  EXPECT_GT(near[0], 2.5 * far[0]) << near[0] << " % near, " << far[0] << " % far";
  EXPECT_LT(near[0], 3.7 * far[0]) << near[0] << " % near, " << far[0] << " % far";
  EXPECT_FALSE(fs::exists(dir_ / "frame_0000.png")) << "preview saves no frame";
}

TEST_F(CaptureCommandTest, SaturatedFractionShowsAnOverexposedFrame) {
  args_.count = 1;
  const std::string normal = Run(/*save_frames=*/false);
  args_.sim_exposure = 2.5;  // the white of the print well beyond full scale
  const std::string over = Run(/*save_frames=*/false);
  ASSERT_EQ(Figures(normal, "saturated").size(), 1u) << normal;
  ASSERT_EQ(Figures(over, "saturated").size(), 1u) << over;
  EXPECT_EQ(Figures(normal, "saturated")[0], 0.0) << normal;
  EXPECT_GT(Figures(over, "saturated")[0], 1.0) << "percent of the pixels at 255: " << over;
  EXPECT_GT(Figures(over, "mean level")[0], Figures(normal, "mean level")[0] + 30.0)
      << normal << over;
}

TEST_F(CaptureCommandTest, PreviewWithDrawKeepsOnePreviewImage) {
  args_.count = 2;
  args_.draw = true;
  args_.sim_pose = {-0.1, -0.1, 8.0, 1, 0, 0, 0};  // 8 m away: 22 px, no board found
  CaptureSummary summary;
  const std::string output = Run(/*save_frames=*/false, &summary);
  EXPECT_EQ(summary.frames, 2);
  EXPECT_EQ(summary.with_board, 0);
  EXPECT_NE(output.find("frame 0: no board, 0/36 tags, 0/144 corners, rms -"), std::string::npos)
      << output;
  EXPECT_FALSE(cv::imread((dir_ / "preview.png").string()).empty());
  EXPECT_FALSE(fs::exists(dir_ / "overlay_0000.png"));
}

// issue 26: a loop of `--count 1` (as on a real camera, one frame per board placement)
// overwrote frame_0000.png every time. Numbering goes on after the frames already there.
TEST_F(CaptureCommandTest, ASecondCaptureAddsFramesInsteadOfOverwriting) {
  args_.board_path = H4_SOURCE_DIR "/boards/checkerboard_9x6_25mm.yaml";
  args_.count = 1;
  const std::string first = Run(/*save_frames=*/true);
  const std::string second = Run(/*save_frames=*/true);
  EXPECT_NE(first.find("frame 0:"), std::string::npos) << first;
  EXPECT_NE(second.find("frame 1:"), std::string::npos) << second;
  EXPECT_NE(second.find("as frame_0001.png to frame_0001.png"), std::string::npos) << second;
  const cv::Mat frame0 = cv::imread((dir_ / "frame_0000.png").string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat frame1 = cv::imread((dir_ / "frame_0001.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(frame0.empty());
  ASSERT_FALSE(frame1.empty()) << "the second capture did not add frame_0001.png";
  // Without --sim-pose the frame number picks the pose: the two frames show the board apart.
  EXPECT_GT(cv::norm(frame0, frame1, cv::NORM_L1) / static_cast<double>(frame0.total()), 5.0);
}

TEST(CaptureFrameNumbering, FollowsTheHighestFrameOrOverlayNumber) {
  EXPECT_EQ(FirstFreeFrameNumber({}), 0);
  EXPECT_EQ(FirstFreeFrameNumber({"notes.txt", "preview.png", "frame_.png", "frame_00a1.png"}), 0);
  EXPECT_EQ(FirstFreeFrameNumber({"frame_0000.png", "frame_0003.png", "overlay_0002.png"}), 4);
  EXPECT_EQ(FirstFreeFrameNumber({"frame_0001.png", "overlay_0007.png"}), 8);
  EXPECT_EQ(FirstFreeFrameNumber({"frame_12345.png"}), 12346);
}

// A chessboard has no tags: its frames read "chessboard: 54/54 corners", not "0/0 tags".
TEST_F(CaptureCommandTest, ChessboardFramesCountCornersNotTags) {
  args_.board_path = H4_SOURCE_DIR "/boards/checkerboard_9x6_25mm.yaml";
  args_.count = 1;
  const std::string output = Run(/*save_frames=*/false);
  EXPECT_NE(output.find("frame 0: board ok, chessboard: 54/54 corners, rms "), std::string::npos)
      << output;
  EXPECT_EQ(output.find("tags"), std::string::npos) << output;
}

}  // namespace
}  // namespace h4::cam

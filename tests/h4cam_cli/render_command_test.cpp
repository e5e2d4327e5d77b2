// Tests for `h4cam render` (firmware/cli/render_command): the preset with the flags
// applied, and errors that name the option at fault.
#include "firmware/cli/render_command.h"

#include <algorithm>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "firmware/cli/capture_command.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

std::string ErrorOf(const RenderArgs& args) {
  try {
    RenderOptionsFromArgs(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RenderCommandTest, SaysWhenTheBoardIsBehindTheCameraOrOffTheImage) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.0, 0.0, 0.0);
  EXPECT_EQ(BoardOutOfView(board, camera, X_CT), "");

  const RigidTransform behind(X_CT.rotation(), -X_CT.translation());
  EXPECT_NE(BoardOutOfView(board, camera, behind).find("behind the camera"), std::string::npos);

  const RigidTransform aside(X_CT.rotation(), X_CT.translation() + Eigen::Vector3d(3.0, 0, 0));
  EXPECT_NE(BoardOutOfView(board, camera, aside).find("off the image"), std::string::npos);
}

TEST(RenderCommandTest, FlagsOverrideThePreset) {
  RenderArgs args;
  args.preset = "processed";
  args.blur_sigma_px = 1.4;
  args.response = "gamma:0.7";
  args.read_noise = 0.5;
  const RenderOptions options = RenderOptionsFromArgs(args);
  EXPECT_EQ(options.blur_sigma_px, 1.4);
  EXPECT_EQ(options.response, ResponseCurve::kGamma);
  EXPECT_EQ(options.response_gamma, 0.7);
  EXPECT_EQ(options.noise_sigma, 0.5);
  // Not overridden: the preset's.
  EXPECT_EQ(options.illumination_gradient, RenderOptions::Processed().illumination_gradient);
  EXPECT_EQ(options.full_well_electrons, RenderOptions::Processed().full_well_electrons);
  // Default preset: processed, as `capture --sim-preset` and `run --sim-preset` (one default
  // for every rendered image, issue 26 point 9).
  EXPECT_EQ(RenderOptionsFromArgs(RenderArgs{}).response, RenderOptions::Processed().response);
  EXPECT_EQ(RenderArgs{}.preset, CaptureArgs{}.sim_preset);
}

TEST(RenderCommandTest, BadValuesAreRejectedNamingTheOption) {
  RenderArgs args;
  args.preset = "vivid";
  EXPECT_NE(ErrorOf(args).find("--preset 'vivid'"), std::string::npos) << ErrorOf(args);
  args = RenderArgs{};
  args.response = "gamma:fast";
  EXPECT_NE(ErrorOf(args).find("--response"), std::string::npos) << ErrorOf(args);
  args = RenderArgs{};
  args.response = "gamma:50";
  EXPECT_NE(ErrorOf(args).find("gamma"), std::string::npos) << ErrorOf(args);
}

// The command line itself rejects absurd values before anything is rendered.
TEST(RenderCommandTest, CommandLineRejectsAbsurdValues) {
  // The values too: --blur 1e4 and --frames 1e8 ran for minutes.
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--blur", "25"},
                                              {"--blur", "1e4"},
                                              {"--frames", "100000"},
                                              {"--frames", "1e8"},
                                              {"--vignetting", "2"},
                                              {"--gradient", "1.5"},
                                              {"--preset", "vivid"},
                                              {"--full-well", "5e8"}}) {
    CLI::App app;
    DeclareRenderCommand(app.add_subcommand("render"));
    std::vector<std::string> argv = {
        "--out",   "/nonexistent/never-written",    "--pose",   "0,0,0.5,1,0,0,0",
        "--board", H4_SOURCE_DIR "/CMakeLists.txt", "--camera", H4_SOURCE_DIR "/CMakeLists.txt"};
    argv.insert(argv.end(), bad.begin(), bad.end());
    argv.insert(argv.begin(), "render");
    std::reverse(argv.begin(), argv.end());  // CLI11 takes them last first
    try {
      app.parse(argv);
      ADD_FAILURE() << "accepted " << bad[0] << " " << bad[1];
    } catch (const CLI::ParseError& e) {  // out of range, or not a number of the option's type
      EXPECT_NE(std::string(e.what()).find(bad[0]), std::string::npos) << e.what();
    } catch (const std::exception& e) {  // another parse error, or rendered
      ADD_FAILURE() << bad[0] << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace h4::cam

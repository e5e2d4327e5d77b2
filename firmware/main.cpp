// h4cam: the camera module's program. One subcommand per file in firmware/cli/; this
// file lists them in its command table, and reports any error once.
#include <CLI/CLI.hpp>

#include "common/cli/command_line.h"
#include "common/cli/subcommand.h"
#include "firmware/cli/calibrate_intrinsics_command.h"
#include "firmware/cli/capture_command.h"
#include "firmware/cli/list_cameras_command.h"
#include "firmware/cli/make_board_command.h"
#include "firmware/cli/measure_command.h"
#include "firmware/cli/render_command.h"
#include "firmware/cli/run_command.h"

namespace {

// Every h4cam subcommand, in the order --help lists them: its name, the line --help shows
// for it, and the function that declares its options (firmware/cli/<name>_command.cpp).
constexpr h4::cli::CommandEntry kCommands[] = {
    {"list-cameras",
     "List the cameras libcamera sees (id and model); exit code 0 also when there is none (\"no "
     "cameras found\")",
     h4::cam::DeclareListCamerasCommand},
    {"calibrate-intrinsics",
     "Camera intrinsics from images of a board (chessboard or AprilTag grid) -> camera YAML",
     h4::cam::DeclareCalibrateIntrinsicsCommand},
    {"make-board", "Printable board at exact scale (SVG, PDF or PNG by the --out extension)",
     h4::cam::DeclareMakeBoardCommand},
    {"render", "Synthetic camera frames of the board at a known pose X_CT",
     h4::cam::DeclareRenderCommand},
    {"measure", "Board poses X_CT from image files (groups of N images averaged)",
     h4::cam::DeclareMeasureCommand},
    {"run", "Camera service: answer capture requests on LCM with board poses (h4cam.service)",
     h4::cam::DeclareRunCommand},
    {"capture",
     "Save camera frames (PNG) for calibrate-intrinsics, printing for each the board's detection, "
     "reprojection RMS, sharpness, exposure and coverage",
     h4::cam::DeclareCaptureCommand},
    {"preview",
     "Aim and focus: print for each frame the board's detection, reprojection RMS, sharpness, "
     "exposure and coverage (with --draw, keep OUT/preview.png up to date)",
     h4::cam::DeclarePreviewCommand},
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"h4cam: camera module of the H4 calibration (measure the board pose X_CT)"};
  h4::cli::SetUpProgram(&app, "h4cam", H4_VERSION);
  h4::cli::AddCommands(app, kCommands);
  return h4::cli::RunCommandLine(&app, "h4cam", argc, argv);
}

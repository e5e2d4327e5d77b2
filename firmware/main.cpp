// h4cam: the camera module's program. One subcommand per file in firmware/cli/; this
// file only lists them, and reports any error once.
#include <CLI/CLI.hpp>

#include "common/cli/command_line.h"
#include "firmware/cli/calibrate_intrinsics_command.h"
#include "firmware/cli/capture_command.h"
#include "firmware/cli/exit_code.h"
#include "firmware/cli/list_cameras_command.h"
#include "firmware/cli/make_board_command.h"
#include "firmware/cli/measure_command.h"
#include "firmware/cli/render_command.h"
#include "firmware/cli/run_command.h"

int main(int argc, char** argv) {
  CLI::App app{"h4cam: camera module of the H4 calibration (measure the board pose X_CT)"};
  h4::cli::SetUpProgram(&app, "h4cam", H4_VERSION);
  h4::cam::AddListCamerasCommand(app);
  h4::cam::AddCalibrateIntrinsicsCommand(app);
  h4::cam::AddMakeBoardCommand(app);
  h4::cam::AddRenderCommand(app);
  h4::cam::AddMeasureCommand(app);
  h4::cam::AddRunCommand(app);
  h4::cam::AddCaptureCommand(app);
  h4::cam::AddPreviewCommand(app);
  return h4::cli::RunCommandLine(&app, "h4cam", argc, argv, h4::cam::ExitCode);
}

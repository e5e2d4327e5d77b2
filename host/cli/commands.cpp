// Registration of every h4cal subcommand, the command line a report shows, and the exit code
// of the commands that leave rows out.
#include "host/cli/commands.h"

#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"

namespace h4::host::cli {

int LeftOutRowsExitCode(size_t left_out, std::string_view what) {
  if (left_out == 0) return h4::cli::kExitSuccess;
  spdlog::error("{} {} (not written)", left_out, what);
  return h4::cli::kExitNothingUsable;
}

std::string ReportCommandLine(const CLI::App& command) {
  std::string line;
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0 || option->get_name() == "--help") continue;
    for (const std::string& value : option->results()) {
      line += option->get_name() + " " + value + " ";
    }
  }
  if (!line.empty()) line.pop_back();
  return line;
}

// Every h4cal subcommand, in the order --help lists them: its name, the line --help shows
// for it, and the function that declares its options (host/cli/<name>_command.cpp; report
// shares validate's file and options).
constexpr h4::cli::CommandEntry kCommands[] = {
    {"simulate", "Simulate a calibration campaign: dataset, a priori robot.yaml and truth",
     DeclareSimulateCommand},
    {"analyze", "Prior kinematic analysis: rotation axis and 4-DoF check from the measured poses",
     DeclareAnalyzeCommand},
    {"identify", "Identify the robot's geometry (Model 12 or 31) from a paired dataset",
     DeclareIdentifyCommand},
    {"fk", "Forward kinematics: joints CSV -> end-effector poses and board poses X_CT",
     DeclareFkCommand},
    {"ik", "Inverse kinematics: end-effector poses CSV -> joints CSV", DeclareIkCommand},
    {"validate",
     "Validation experiments (paper IV.D): joint residuals (Table 3), straightness (Table 4), "
     "square path, 4-DoF check",
     DeclareValidateCommand},
    {"report", "Write the calibration report (one self-contained HTML file) to DIR/report.html",
     DeclareReportCommand},
    {"export", "Export an identification result for the controller (robot.yaml keys)",
     DeclareExportCommand},
    {"collect",
     "Calibration campaign over LCM: move the robot through a pose plan, measure the board at each "
     "pose and append the paired rows to a dataset CSV (resumable)",
     DeclareCollectCommand},
    {"sim-robot",
     "Simulated H4 controller on LCM: takes H4_ROBOT_TARGET, publishes H4_JOINT_STATE and the true "
     "board pose on H4_SIM_BOARD_TRUTH (for h4cam run --source sim)",
     DeclareSimRobotCommand},
    {"square-plan",
     "Write the commanded points of the square-path validation as a poses CSV (pose_id,X,Y,Z,theta "
     "in B), for h4cal collect --plan --controller",
     DeclareSquarePlanCommand},
    {"plan",
     "Plan N calibration poses (the most accurate design for the identification) among the poses "
     "the robot reaches with the whole board in the image; writes a poses CSV for h4cal collect "
     "--plan",
     DeclarePlanCommand},
    {"check",
     "Check that the robot still matches an identification result, from a short verification "
     "campaign; exit 3 when it has drifted",
     DeclareCheckCommand},
};

void AddAllCommands(CLI::App& app) { h4::cli::AddCommands(app, kCommands); }

}  // namespace h4::host::cli

// Registration of every h4cal subcommand, and the run's exit code.
#include "host/cli/commands.h"

namespace h4::host::cli {
namespace {
int g_exit_code = 0;
}  // namespace

void AddAllCommands(CLI::App& app) {
  AddSimulateCommand(app);
  AddAnalyzeCommand(app);
  AddIdentifyCommand(app);
  AddFkCommand(app);
  AddIkCommand(app);
  AddValidateCommand(app);
  AddReportCommand(app);
  AddExportCommand(app);
  AddCollectCommand(app);
  AddSimRobotCommand(app);
  AddSquarePlanCommand(app);
  AddPlanCommand(app);
  AddCheckCommand(app);
}

int ExitCode() { return g_exit_code; }
void SetExitCode(int code) { g_exit_code = code; }

}  // namespace h4::host::cli

// Registration of every h4cal subcommand, the command line a report shows, and the run's exit
// code.
#include "host/cli/commands.h"

namespace h4::host::cli {
namespace {
int g_exit_code = 0;
}  // namespace

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

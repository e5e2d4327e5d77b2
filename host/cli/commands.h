// The h4cal subcommands. Each lives in its own <name>_command.cpp and registers
// itself on the app; a command reports a failure by throwing (main prints it once)
// or, for "ran but the result is not usable", by SetExitCode.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace h4::host::cli {

void AddSimulateCommand(CLI::App& app);
void AddIdentifyCommand(CLI::App& app);
void AddAnalyzeCommand(CLI::App& app);
void AddFkCommand(CLI::App& app);
void AddIkCommand(CLI::App& app);
void AddValidateCommand(CLI::App& app);
void AddReportCommand(CLI::App& app);
void AddExportCommand(CLI::App& app);
void AddCollectCommand(CLI::App& app);
void AddSimRobotCommand(CLI::App& app);
void AddSquarePlanCommand(CLI::App& app);
void AddPlanCommand(CLI::App& app);
void AddCheckCommand(CLI::App& app);

/// The options a subcommand was given, as "--name value ..." (shown in the report).
std::string ReportCommandLine(const CLI::App& command);

/// Registers every command above.
void AddAllCommands(CLI::App& app);

/// Exit code of the run: 0 unless a command set one (e.g. 3: finished, result unusable).
int ExitCode();
void SetExitCode(int code);

}  // namespace h4::host::cli

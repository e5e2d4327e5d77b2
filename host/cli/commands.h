// The h4cal subcommands. Each lives in its own <name>_command.cpp and registers
// itself on the app; a command reports a failure by throwing (main prints it once)
// or, for "ran but the result is not usable", by SetExitCode.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "common/cli/subcommand.h"

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

/// Has `command` call run(options, "h4cal <command> <its ReportCommandLine>") once the
/// command line is parsed: the commands whose report shows how it was made.
template <typename Options, typename Run = void (*)(const Options&, const std::string&)>
void RunWithCommandLineWhenParsed(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  h4::cli::RunWhenParsed(command, std::move(options), [command, run](Options& parsed) {
    run(parsed, "h4cal " + command->get_name() + " " + ReportCommandLine(*command));
  });
}

/// Registers every command above.
void AddAllCommands(CLI::App& app);

/// Exit code of the run: 0 unless a command set one (e.g. 3: finished, result unusable).
int ExitCode();
void SetExitCode(int code);

}  // namespace h4::host::cli

// The h4cal subcommands. Each lives in its own <name>_command.cpp, which declares its
// options and what it runs (Declare*Command); commands.cpp lists them with their names in
// the program's command table. A command reports a failure by throwing (main prints it
// once) or, for "ran but the result is not usable", by returning its exit code
// (common/cli/subcommand.h).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include <CLI/CLI.hpp>

#include "common/cli/subcommand.h"

namespace h4::host::cli {

void DeclareSimulateCommand(CLI::App* command);
void DeclareIdentifyCommand(CLI::App* command);
void DeclareAnalyzeCommand(CLI::App* command);
void DeclareFkCommand(CLI::App* command);
void DeclareIkCommand(CLI::App* command);
void DeclareValidateCommand(CLI::App* command);
void DeclareReportCommand(CLI::App* command);
void DeclareExportCommand(CLI::App* command);
void DeclareCollectCommand(CLI::App* command);
void DeclareSimRobotCommand(CLI::App* command);
void DeclareSquarePlanCommand(CLI::App* command);
void DeclarePlanCommand(CLI::App* command);
void DeclareCheckCommand(CLI::App* command);

/// The options a subcommand was given, as "--name value ..." (shown in the report).
std::string ReportCommandLine(const CLI::App& command);

/// Has `command` call run(options, "h4cal <command> <its ReportCommandLine>") once the
/// command line is parsed: the commands whose report shows how it was made. A `run` that
/// returns an int returns the exit code, as for h4::cli::RunWhenParsed.
template <typename Options, typename Run = void (*)(const Options&, const std::string&)>
void RunWithCommandLineWhenParsed(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  h4::cli::RunWhenParsed(command, std::move(options), [command, run](Options& parsed) {
    return run(parsed, "h4cal " + command->get_name() + " " + ReportCommandLine(*command));
  });
}

/// The exit code of a command that writes the rows it can and leaves the others out (fk, ik):
/// kExitNothingUsable after logging "<left_out> <what> (not written)" when any was left out,
/// kExitSuccess otherwise.
int LeftOutRowsExitCode(size_t left_out, std::string_view what);

/// Registers every command above.
void AddAllCommands(CLI::App& app);

}  // namespace h4::host::cli

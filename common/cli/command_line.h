// The command-line conventions h4cal and h4cam share (README.md#using-h4cal): an
// option's first long name is its name, further long names are old spellings that stay
// accepted and are not shown in --help; one error line, "<program>: error: <what>", where
// <what> names the file, line and field (common/formats/format_error.h); the exit codes.
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace h4::cli {

/// Exit codes, the same for both programs (README.md#using-h4cal).
constexpr int kExitSuccess = 0;
constexpr int kExitError = 1;
/// The command ran but nothing usable came out (skipped poses, no board seen, a verdict
/// other than good); what it wrote stays written.
constexpr int kExitNothingUsable = 3;
/// Interrupted (Ctrl-C or SIGTERM): 128 + SIGINT, as a shell reports it.
constexpr int kExitInterrupted = 130;

/// --help that lists an option under its short names and first long name only: the other
/// long names are the old spellings scripts may still use ("--out-dir,--out").
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool is_positional) const override;
};

/// A program's top-level app with the shared formatter and `--version` ("<program>
/// <version>"). Set before any subcommand is added: subcommands copy the formatter.
void SetUpProgram(CLI::App* app, const std::string& program, const std::string& version);

/// The one error line both programs print (without its newline).
std::string ErrorLine(const std::string& program, const std::string& what);

/// Parses and runs the chosen subcommand. Usage errors, --help and --version go through
/// CLI11 (exit 0, or 100 and above); an exception a command throws is printed once as
/// ErrorLine on stderr (exit 1); otherwise the code the command returned
/// (common/cli/subcommand.h, RunWhenParsed), 0 for a command that returns nothing.
int RunCommandLine(CLI::App* app, const std::string& program, int argc, char** argv);

}  // namespace h4::cli

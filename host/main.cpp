// h4cal: the workstation program. Parses the command line, hands over to one
// subcommand (host/cli/*_command.cpp), and reports any error once, here.
#include <cstdio>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "host/cli/commands.h"
#include "host/cli/log_style.h"

int main(int argc, char** argv) {
  // Results go to stdout, the log to stderr, so a script can capture one without the other.
  // Line by line, so that both sent to one file (2>&1) interleave in the order they happened
  // rather than stdout's lines arriving in 4 KiB blocks cut mid-line.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  h4::host::cli::UseProgramLogStyle("h4cal");
  CLI::App app{
      "h4cal: vision-based kinematic calibration of H4 parallel robots (Renaud et al., ICRA "
      "2003).\nSee README.md; conventions in common/README.md, formats in "
      "common/formats/README.md."};
  h4::cli::SetUpProgram(&app, "h4cal", H4_VERSION);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log debug details");
  app.parse_complete_callback(
      [&verbose] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });
  h4::host::cli::AddAllCommands(app);
  return h4::cli::RunCommandLine(&app, "h4cal", argc, argv);
}

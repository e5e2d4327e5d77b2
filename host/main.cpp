// h4cal: the workstation program. Parses the command line, hands over to one
// subcommand (host/cli/*_command.cpp), and reports any error once, here.
#include <exception>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "host/cli/commands.h"

int main(int argc, char** argv) {
  // Results go to stdout, the log to stderr, so a script can capture one without the other.
  spdlog::set_default_logger(spdlog::stderr_color_mt("h4cal"));
  CLI::App app{
      "h4cal: vision-based kinematic calibration of H4 parallel robots (Renaud et al., ICRA "
      "2003).\nSee README.md; conventions in common/README.md, formats in "
      "common/formats/README.md."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("h4cal ") + H4_VERSION);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log debug details");
  app.parse_complete_callback(
      [&verbose] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });
  h4::host::cli::AddAllCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);  // help, version, or a usage error (exit code 2 family)
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return h4::host::cli::ExitCode();
}

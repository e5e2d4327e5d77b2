// The shared help formatter, --version and error line; see command_line.h.
#include "common/cli/command_line.h"

#include <exception>
#include <iostream>

namespace h4::cli {

std::string HelpFormatter::make_option_name(const CLI::Option* option, bool is_positional) const {
  if (is_positional || option->get_lnames().empty()) {
    return CLI::Formatter::make_option_name(option, is_positional);
  }
  std::string names;
  for (const std::string& short_name : option->get_snames()) names += "-" + short_name + ",";
  return names + "--" + option->get_lnames().front();
}

void SetUpProgram(CLI::App* app, const std::string& program, const std::string& version) {
  app->formatter(std::make_shared<HelpFormatter>());
  app->require_subcommand(1);
  app->set_version_flag("--version", program + " " + version);
}

std::string ErrorLine(const std::string& program, const std::string& what) {
  return program + ": error: " + what;
}

int RunCommandLine(CLI::App* app, const std::string& program, int argc, char** argv) {
  try {
    app->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help, version, a usage error (100 and above), or a command's own exit code
    // (CLI::RuntimeError, which CLI::App::exit returns without printing).
    return app->exit(e);
  } catch (const std::exception& e) {
    std::cerr << ErrorLine(program, e.what()) << "\n";
    return kExitError;
  }
  return kExitSuccess;
}

}  // namespace h4::cli

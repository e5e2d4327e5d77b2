// `h4cal report`: the calibration report, one self-contained HTML file with the validation
// tables and figures (host/report), from the same inputs as `h4cal validate`.
#include <memory>

#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "host/cli/commands.h"
#include "host/cli/validation_inputs.h"
#include "host/report/html_report.h"

namespace h4::host::cli {

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

namespace {

struct ReportOptions {
  ValidationFileOptions files;
  std::string out_dir;
};

void Run(const ReportOptions& options, const std::string& command_line) {
  const ValidationInputs inputs = LoadValidationInputs(options.files);
  const ValidationReport report = Validate(inputs);
  const std::string path = WriteHtmlReport(options.out_dir, inputs, report, command_line);
  spdlog::info("wrote {}", path);
}

}  // namespace

void AddReportCommand(CLI::App& app) {
  const auto [command, options] = h4::cli::AddSubcommand<ReportOptions>(
      app, "report",
      "Write the calibration report (one self-contained HTML file) to DIR/report.html");
  AddValidationFileOptions(command, &options->files);
  h4::cli::AddOutDirOption(command, &options->out_dir, "Folder of report.html", "--report-dir")
      ->required();
  RunWithCommandLineWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli

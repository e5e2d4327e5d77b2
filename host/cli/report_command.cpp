// `h4cal report`: the calibration report, one self-contained HTML file with the validation
// tables and figures (host/report), from the same inputs as `h4cal validate`.
#include <memory>

#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
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

void AddReportCommand(CLI::App& app) {
  auto files = std::make_shared<ValidationFileOptions>();
  auto out_dir = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "report", "Write the calibration report (one self-contained HTML file) to DIR/report.html");
  AddValidationFileOptions(command, files.get());
  h4::cli::AddOutDirOption(command, out_dir.get(), "Folder of report.html", "--report-dir")
      ->required();
  command->callback([files, out_dir, command] {
    const ValidationInputs inputs = LoadValidationInputs(*files);
    const ValidationReport report = Validate(inputs);
    const std::string path =
        WriteHtmlReport(*out_dir, inputs, report, "h4cal report " + ReportCommandLine(*command));
    spdlog::info("wrote {}", path);
  });
}

}  // namespace h4::host::cli

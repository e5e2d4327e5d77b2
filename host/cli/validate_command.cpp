// `h4cal validate` and `h4cal report`: the paper's validation experiments (IV.D) on
// identification results and data: Table 3 on the held-out poses, Table 4 straightness, the
// square path under the Model 12 control law (simulation), the 4-DoF check. validate prints
// them, and with --report DIR writes the HTML report too; report writes the report only (one
// self-contained HTML file with the validation tables and figures, host/report).
#include <memory>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "host/cli/calibration_workflow.h"
#include "host/cli/commands.h"
#include "host/cli/validation_inputs.h"

namespace h4::host::cli {
namespace {

struct ValidateOptions {
  ValidationFileOptions files;
  std::string report_dir;    ///< where report.html goes; "": no report
  bool print_tables = true;  ///< validate prints the tables, report does not
};

void Run(const ValidateOptions& options, const std::string& command_line) {
  ValidateAndReport(options.files, options.report_dir, command_line, options.print_tables);
}

}  // namespace

void DeclareValidateCommand(CLI::App* command) {
  const auto options = std::make_shared<ValidateOptions>();
  AddValidationFileOptions(command, &options->files);
  h4::cli::AddReportDirOption(command, &options->report_dir);
  RunWithCommandLineWhenParsed(command, options, Run);
}

void DeclareReportCommand(CLI::App* command) {
  const auto options = std::make_shared<ValidateOptions>();
  options->print_tables = false;
  AddValidationFileOptions(command, &options->files);
  // --report-dir as in identify, validate and collect: one name for the report's folder.
  command->add_option("--report-dir,--out-dir", options->report_dir, "Folder of report.html")
      ->required();
  RunWithCommandLineWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli

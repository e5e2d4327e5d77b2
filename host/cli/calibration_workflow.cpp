// The one path from an identification to its report; see calibration_workflow.h.
#include "host/cli/calibration_workflow.h"

#include <cstdio>
#include <ctime>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "host/report/html_report.h"

namespace h4::host::cli {
namespace {

std::string UtcTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

ResultProvenance ProvenanceOf(const std::vector<std::string>& inputs) {
  return ResultProvenance{H4_VERSION, UtcTimestamp(), inputs};
}

void WriteResultWithProvenance(const std::string& path, IdentificationResult result,
                               const std::vector<std::string>& inputs) {
  result.provenance = ProvenanceOf(inputs);
  WriteIdentificationResult(path, result);
}

void AddCornersIfRecorded(const std::string& corners_path, const std::string& board_path,
                          const std::string& camera_path, ValidationFileOptions* files) {
  if (corners_path.empty() || board_path.empty() || camera_path.empty()) return;
  if (!std::filesystem::exists(corners_path)) return;
  files->corners_path = corners_path;
  files->board_path = board_path;
  files->camera_path = camera_path;
}

ValidationReport ValidateAndReport(const ValidationFileOptions& files,
                                   const std::string& report_dir,
                                   const std::string& command_line, bool print_text) {
  const ValidationInputs inputs = LoadValidationInputs(files);
  ValidationReport report = Validate(inputs);
  if (print_text) std::fputs(FormatValidationText(report).c_str(), stdout);
  if (!report_dir.empty()) {
    spdlog::info("wrote {}", WriteHtmlReport(report_dir, inputs, report, command_line));
  }
  return report;
}

}  // namespace h4::host::cli

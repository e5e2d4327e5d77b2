// The one path from an identification to its report (issue 43 point 5): `identify`,
// `collect --report-dir`, the sequential campaign's first stage and `validate` / `report`
// write results and reports through these, so that every result carries its provenance and
// every report the same sections from the same files.
#pragma once

#include <string>
#include <vector>

#include "host/cli/validation_inputs.h"
#include "host/formats/identification_result.h"
#include "host/validation/validation.h"

namespace h4::host::cli {

/// Who made a result, when (UTC), from which files: this h4cal's version and `inputs`.
ResultProvenance ProvenanceOf(const std::vector<std::string>& inputs);

/// Writes `result` to `path` (atomically) with the provenance of `inputs`.
void WriteResultWithProvenance(const std::string& path, IdentificationResult result,
                               const std::vector<std::string>& inputs);

/// The files of a campaign's report beside its dataset: the corners, board and camera when
/// the corners file exists and both others are given (the report's camera section), else
/// none.
void AddCornersIfRecorded(const std::string& corners_path, const std::string& board_path,
                          const std::string& camera_path, ValidationFileOptions* files);

/// Reads the files, validates, prints the validation's text when `print_text`, writes
/// report.html in `report_dir` (none when empty) and returns the report.
ValidationReport ValidateAndReport(const ValidationFileOptions& files,
                                   const std::string& report_dir,
                                   const std::string& command_line, bool print_text);

}  // namespace h4::host::cli

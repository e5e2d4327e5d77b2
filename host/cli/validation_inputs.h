// The inputs of `h4cal validate` and `h4cal report` (shared options): the a priori
// robot.yaml, the dataset, the Model 12 / Model 31 results, the ruler runs, the truth of a
// simulation and the square size; or --sim-dir, the folder `h4cal simulate` wrote.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "host/validation/validation.h"

namespace h4::host::cli {

struct ValidationFileOptions {
  std::string sim_dir;  ///< --sim-dir: defaults for every file below from a simulate folder
  std::string robot_path;
  std::string data_path;
  std::string result12_path;
  std::string result31_path;
  std::string truth_path;
  std::vector<std::string> straightness_paths;
  double square_mm = 100.0;
};

void AddValidationFileOptions(CLI::App* command, ValidationFileOptions* options);

/// Reads every file; throws naming the file on any problem (missing file, wrong model).
ValidationInputs LoadValidationInputs(const ValidationFileOptions& options);

/// Table 3, positioning, Table 4, square and 4-DoF as text, for stdout.
std::string FormatValidationText(const ValidationReport& report);

}  // namespace h4::host::cli

// The inputs of `h4cal validate` and `h4cal report` (shared options): the a priori
// robot.yaml, the dataset, the Model 12 / Model 31 results, the ruler runs, the truth of a
// simulation and the square size, the square runs measured on the robot (plan and
// datasets); or --sim-dir, the folder `h4cal simulate` wrote.
#pragma once

#include <optional>
#include <string>
#include <utility>
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
  bool square_mm_given = false;  ///< --square-mm was on the command line
  std::string square_plan_path;  ///< --square-plan: poses CSV of `h4cal square-plan`
  /// --square-measured LABEL=DATASET, repeatable: a dataset collected along the plan by the
  /// LABEL controller (e.g. "a priori=sq_apriori.csv").
  std::vector<std::string> square_measured;
  /// --corners, --board, --camera: the corners h4cam measured with the dataset's poses
  /// (identify --corners' files), for the report's corner residual map.
  std::string corners_path;
  std::string board_path;
  std::string camera_path;
};

/// Splits "LABEL=DATASET" at its first '='; throws std::invalid_argument when either part
/// is empty or there is no '='.
std::pair<std::string, std::string> SplitSquareMeasured(const std::string& value);

/// The identified model a --square-measured LABEL names as the one that drove the run:
/// "Model 12", "model31", "31" (case and spaces aside); nullopt for any other controller
/// ("a priori").
std::optional<ModelKind> ModelDrivingSquare(const std::string& label);

void AddValidationFileOptions(CLI::App* command, ValidationFileOptions* options);

/// The console lines of the measured square runs: each run's shape (offset removed) first,
/// then its side errors and offset in the frame it is judged in, and what the offset is.
std::string MeasuredSquareLines(const std::vector<MeasuredSquareRun>& runs);

/// Reads every file; throws naming the file on any problem (missing file, wrong model).
ValidationInputs LoadValidationInputs(const ValidationFileOptions& options);

/// Table 3, positioning, Table 4, square and 4-DoF as text, for stdout.
std::string FormatValidationText(const ValidationReport& report);

}  // namespace h4::host::cli

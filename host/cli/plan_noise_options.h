// What the planner is told of the measurement it plans for, one set of options for `plan`
// and `collect --sequential` (issue 44): the camera's corner noise and how far the camera
// may sit from robot.yaml's X_BC.
#pragma once

#include <CLI/CLI.hpp>

#include "common/units.h"
#include "host/planning/pose_planner.h"

namespace h4::host::cli {

struct PlanNoiseOptions {
  double corner_sigma_px = 0.0;  ///< PlanningProblemOptions::corner_sigma_px
  /// The camera set-up spread of the drawn robots (RobustOptions::spread), mm and deg.
  double setup_sigma_mm = 1e3 * RobustOptions{}.spread.camera_translation_std;
  double setup_sigma_deg = DegreesFromRadians(RobustOptions{}.spread.camera_rotation_std);
};

/// --corner-sigma-px, --setup-sigma-mm, --setup-sigma-deg, with their defaults shown.
void AddPlanNoiseOptions(CLI::App* command, PlanNoiseOptions* options);

/// Sets them in `problem`; throws std::invalid_argument naming the option on a corner sigma
/// outside the corners CSV's bounds.
void ApplyPlanNoise(const PlanNoiseOptions& noise, PlanningProblemOptions* problem);

}  // namespace h4::host::cli

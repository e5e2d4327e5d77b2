// The planner's measurement options; see plan_noise_options.h.
#include "host/cli/plan_noise_options.h"

#include <stdexcept>
#include <string>

#include "common/cli/shared_options.h"

namespace h4::host::cli {

void AddPlanNoiseOptions(CLI::App* command, PlanNoiseOptions* options) {
  h4::cli::AddOptionShowingDefault(
      command, "--setup-sigma-mm", &options->setup_sigma_mm,
      "How far the camera may be from robot.yaml's X_BC, one sigma per axis, mm "
      "(the drawn robots' cameras; candidates one of them misses are left out). A mount "
      "measured with a tape: 10",
      CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(command, "--setup-sigma-deg", &options->setup_sigma_deg,
                                   "The same for the camera's orientation, deg (a mount "
                                   "measured with a tape: 1)",
                                   CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(
      command, "--corner-sigma-px", &options->corner_sigma_px,
      "Corner noise of the camera, px: each pose's noise from the board pose "
      "solved from its corners, as the camera reports it (0: 0.2 mm, 0.03 deg "
      "for every pose, as a dataset without sigma columns); else within the corners CSV's "
      "sigma_px bounds, 1e-06..100",
      CLI::NonNegativeNumber);
}

void ApplyPlanNoise(const PlanNoiseOptions& noise, PlanningProblemOptions* problem) {
  problem->corner_sigma_px = noise.corner_sigma_px;
  std::string why;
  if (!problem->IsValid(&why)) throw std::invalid_argument("--corner-sigma-px: " + why);
  problem->robust.spread.camera_translation_std = 1e-3 * noise.setup_sigma_mm;
  problem->robust.spread.camera_rotation_std = RadiansFromDegrees(noise.setup_sigma_deg);
}

}  // namespace h4::host::cli

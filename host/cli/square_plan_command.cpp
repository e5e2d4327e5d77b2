// `h4cal square-plan`: the commanded points of the square-path validation (paper IV.D) as a
// poses CSV (common/formats/README.md: pose_id,X,Y,Z,theta in B), for `h4cal collect --plan
// --controller` to drive a real robot through with the IK control law of the model found accurate
// (Model 12, or Model 31 with --robot: host/campaign/control_law.h). The points are
// those of the simulated square (host/validation/square_path.h, SquarePoints), so `h4cal validate
// --square-plan --square-measured` compares the measured path with the same square.
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/formats/poses_csv.h"
#include "host/validation/measured_square.h"

namespace h4::host::cli {
namespace {

struct SquarePlanCommandOptions {
  std::string out_path;
  double side_mm = 100.0;
  int points_per_side = 21;
  std::string centre = "0,0,-0.45";  ///< X,Y,Z in B, m
  double theta_deg = 0.0;
  int64_t first_id = 1001;
};

// "X,Y,Z" (m) as a vector; throws naming the option on anything else.
Eigen::Vector3d ParseCentre(const std::string& text) {
  Eigen::Vector3d centre;
  const char* at = text.c_str();
  for (int k = 0; k < 3; ++k) {
    char* end = nullptr;
    centre[k] = std::strtod(at, &end);
    const bool separator_ok = k < 2 ? *end == ',' : *end == '\0';
    if (end == at || !separator_ok || !std::isfinite(centre[k])) {
      throw std::invalid_argument(
          fmt::format("--centre \"{}\": expected X,Y,Z in metres (e.g. 0,0,-0.45)", text));
    }
    at = end + 1;
  }
  return centre;
}

void Run(const SquarePlanCommandOptions& o) {
  SquareOptions square;
  square.side = o.side_mm * 1e-3;
  square.points_per_side = o.points_per_side;
  square.centre = ParseCentre(o.centre);
  square.theta = RadiansFromDegrees(o.theta_deg);
  if (const std::string problem = square.Problem(); !problem.empty()) {
    throw std::invalid_argument("square-plan: " + problem +
                                " (--square-mm > 0, --points-per-side >= 2)");
  }
  const std::vector<EndEffectorPoseRow> rows = SquarePlanPoses(square, o.first_id);
  WritePosesCsv(o.out_path, rows);
  spdlog::info(
      "wrote {} points to {}: a {:.1f} mm square centred at ({:.1f}, {:.1f}, {:.1f}) mm, theta "
      "{:.2f} deg, 4 sides of {} points (each corner twice), pose ids {}..{}",
      rows.size(), o.out_path, o.side_mm, square.centre[0] * 1e3, square.centre[1] * 1e3,
      square.centre[2] * 1e3, o.theta_deg, square.points_per_side, rows.front().pose_id,
      rows.back().pose_id);
}

}  // namespace

void DeclareSquarePlanCommand(CLI::App* command) {
  const auto options = std::make_shared<SquarePlanCommandOptions>();
  h4::cli::AddOutOption(command, &options->out_path, "Output poses CSV");
  // The same name as validate's side of the square.
  command->add_option("--square-mm,--side-mm", options->side_mm, "Side of the square, mm")
      ->capture_default_str();
  command
      ->add_option("--points-per-side", options->points_per_side,
                   "Points per side, both corners included (each corner is commanded twice: "
                   "end of a side, start of the next)")
      ->capture_default_str();
  command->add_option("--centre", options->centre, "Centre X,Y,Z in B, m")->capture_default_str();
  command->add_option("--theta-deg", options->theta_deg, "Nacelle angle along the square, deg")
      ->capture_default_str();
  command->add_option("--first-id", options->first_id, "pose_id of the first point")
      ->capture_default_str();
  command->footer(
      "Writes 4 * points-per-side rows in path order: corner (-,-) to (+,-), (+,-) to (+,+), "
      "(+,+) to (-,+), (-,+) to (-,-) in the X-Y plane of B. Measure it with h4cal collect "
      "--plan OUT --controller result.json|controller.yaml [--robot robot.yaml for a Model 31 "
      "result], then h4cal validate --square-plan OUT "
      "--square-measured LABEL=DATASET.");
  h4::cli::RunWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli

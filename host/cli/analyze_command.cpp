// `h4cal analyze`: the prior kinematic analysis of paper III.B: the rotation axis from the
// measured R_CT alone, its spread (the 4-DoF check; the paper measured 0.12 deg), and the
// corrections it implies for the a priori X_BC / X_TE.
#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/identification/prior_analysis.h"

namespace h4::host::cli {
namespace {

struct AnalyzeOptions {
  std::string robot_path;
  std::string data_path;
};

// A placement as people read it: mm and deg (the files keep m and rad).
void PrintPlacement(const char* name, const RigidTransform& X) {
  const Eigen::Vector3d p_mm = 1e3 * X.translation(), rpy = X.rpy();
  fmt::print("{}: translation [{:.2f}, {:.2f}, {:.2f}] mm, rpy [{:.4f}, {:.4f}, {:.4f}] deg\n",
             name, p_mm.x(), p_mm.y(), p_mm.z(), DegreesFromRadians(rpy.x()),
             DegreesFromRadians(rpy.y()), DegreesFromRadians(rpy.z()));
}

void Run(const AnalyzeOptions& options) {
  const RobotDescription robot = ReadRobotYaml(options.robot_path);
  const std::vector<DatasetRow> rows = ReadDatasetCsv(options.data_path);
  const PriorAnalysis a = AnalyzeRotationAxis(rows, robot.X_BC, robot.X_TE);
  if (!a.ok) throw std::runtime_error(options.data_path + ": prior analysis failed: " + a.message);
  fmt::print("rotation axis in the camera frame C: ({:.6f}, {:.6f}, {:.6f})\n", a.axis_C.x(),
             a.axis_C.y(), a.axis_C.z());
  fmt::print("rotation axis in the board frame T:  ({:.6f}, {:.6f}, {:.6f})\n", a.axis_T.x(),
             a.axis_T.y(), a.axis_T.z());
  fmt::print("4-DoF check: axis spread {:.4f} deg RMS over {} poses (paper: 0.12 deg)\n",
             a.axis_spread_deg, a.poses_used);
  fmt::print("a priori camera z axis off by {:.3f} deg, board z axis off by {:.3f} deg\n",
             a.camera_axis_correction_deg, a.board_axis_correction_deg);
  PrintPlacement("initial X_BC", a.X_BC);
  PrintPlacement("initial X_TE", a.X_TE);
  spdlog::info("{}", a.message);
}

}  // namespace

void DeclareAnalyzeCommand(CLI::App* command) {
  const auto options = std::make_shared<AnalyzeOptions>();
  h4::cli::AddRobotOption(command, &options->robot_path)->required();
  h4::cli::AddDataOption(command, &options->data_path)->required();
  h4::cli::RunWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli

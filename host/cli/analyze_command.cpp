// `h4cal analyze`: the prior kinematic analysis of paper III.B: the rotation axis from the
// measured R_CT alone, its spread (the 4-DoF check; the paper measured 0.12 deg), and the
// corrections it implies for the a priori X_BC / X_TE.
#include <spdlog/spdlog.h>

#include "common/formats/dataset_csv.h"
#include "common/formats/robot_yaml.h"
#include "host/cli/commands.h"
#include "host/identification/prior_analysis.h"

namespace h4::host::cli {
namespace {

struct AnalyzeOptions {
  std::string robot_path;
  std::string data_path;
};

void Run(const AnalyzeOptions& options) {
  const RobotDescription robot = ReadRobotYaml(options.robot_path);
  const std::vector<DatasetRow> rows = ReadDatasetCsv(options.data_path);
  const PriorAnalysis a = AnalyzeRotationAxis(rows, robot.X_BC, robot.X_TE);
  if (!a.ok) throw std::runtime_error(options.data_path + ": prior analysis failed: " + a.message);
  std::printf("rotation axis in the camera frame C: (%.6f, %.6f, %.6f)\n", a.axis_C.x(),
              a.axis_C.y(), a.axis_C.z());
  std::printf("rotation axis in the board frame T:  (%.6f, %.6f, %.6f)\n", a.axis_T.x(),
              a.axis_T.y(), a.axis_T.z());
  std::printf("4-DoF check: axis spread %.4f deg RMS over %d poses (paper: 0.12 deg)\n",
              a.axis_spread_deg, a.poses_used);
  std::printf("a priori camera z axis off by %.3f deg, board z axis off by %.3f deg\n",
              a.camera_axis_correction_deg, a.board_axis_correction_deg);
  const Eigen::Vector3d t = a.X_BC.translation(), rpy = a.X_BC.rpy();
  std::printf("initial X_BC: translation [%.5f, %.5f, %.5f] m, rpy [%.5f, %.5f, %.5f] rad\n", t.x(),
              t.y(), t.z(), rpy.x(), rpy.y(), rpy.z());
  const Eigen::Vector3d t2 = a.X_TE.translation(), rpy2 = a.X_TE.rpy();
  std::printf("initial X_TE: translation [%.5f, %.5f, %.5f] m, rpy [%.5f, %.5f, %.5f] rad\n",
              t2.x(), t2.y(), t2.z(), rpy2.x(), rpy2.y(), rpy2.z());
  spdlog::info("{}", a.message);
}

}  // namespace

void AddAnalyzeCommand(CLI::App& app) {
  auto options = std::make_shared<AnalyzeOptions>();
  CLI::App* command = app.add_subcommand(
      "analyze", "Prior kinematic analysis: rotation axis and 4-DoF check from the measured poses");
  command->add_option("--robot", options->robot_path, "A priori robot.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--data", options->data_path, "Paired dataset CSV")
      ->required()
      ->check(CLI::ExistingFile);
  command->callback([options] { Run(*options); });
}

}  // namespace h4::host::cli

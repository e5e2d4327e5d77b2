// `h4cal check`: does the robot still match an identification result? Reads a short
// verification campaign (a dataset CSV, e.g. 5 poses from `h4cal plan --count 5 --for-check`
// measured with `h4cal collect --plan`), compares each measured board pose with the result's
// prediction from the joints and flags the poses whose error exceeds what the measurement
// noise and the result's uncertainty allow (host/validation/drift_check.h). Exit 3 on drift.
#include <stdexcept>

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/formats/robot_yaml.h"
#include "host/validation/drift_check.h"

namespace h4::host::cli {
namespace {

struct CheckCommandOptions {
  std::string result_path, data_path, robot_path;
  DriftCheckOptions check;
  /// Judge against the measurement noise alone, ignoring the result's uncertainty.
  bool no_parameter_sigmas = false;
  /// Judge against the camera's stated pose covariance, without the result's factor.
  bool stated_camera_covariance = false;
};

void PrintPoses(const DriftCheckResult& check) {
  fmt::print("  pose_id   position mm   rotation deg      d^2  verdict\n");
  for (const PoseCheck& pose : check.poses) {
    fmt::print("  {:7} {:>13.4f} {:>14.4f} {:>8.2f}  {}\n", static_cast<long long>(pose.pose_id),
               pose.position_error * 1e3, DegreesFromRadians(pose.rotation_error),
               pose.mahalanobis2, pose.flagged ? "FLAGGED" : "ok");
  }
}

int Run(const CheckCommandOptions& o) {
  const IdentificationResult result = ReadIdentificationResult(o.result_path);
  const Assembly assembly =
      o.robot_path.empty() ? Assembly{} : ReadRobotYaml(o.robot_path).assembly;
  const std::vector<DatasetRow> rows = ReadDatasetCsv(o.data_path);
  const DriftCheckResult check = CheckResultForDrift(
      result, assembly, rows, o.check, !o.no_parameter_sigmas, !o.stated_camera_covariance);
  fmt::print("check of {} against {} (Model {}), {} poses:\n", o.data_path, o.result_path,
             ToString(result.model), rows.size());
  if (check.evaluable) PrintPoses(check);
  fmt::print("{}\n", check.Summary());
  return check.drift ? h4::cli::kExitNothingUsable : h4::cli::kExitSuccess;
}

}  // namespace

void DeclareCheckCommand(CLI::App* command) {
  const auto options = std::make_shared<CheckCommandOptions>();
  h4::cli::AddResultOption(command, &options->result_path)->required();
  h4::cli::AddDataOption(command, &options->data_path, "Verification dataset CSV")->required();
  h4::cli::AddRobotOption(command, &options->robot_path,
                          "robot.yaml to take the assembly signs from");
  command
      ->add_option("--pose-false-alarm", options->check.pose_false_alarm,
                   "Probability that an unchanged robot has a pose flagged")
      ->capture_default_str();
  command
      ->add_option("--total-false-alarm", options->check.total_false_alarm,
                   "Probability that an unchanged robot fails the chi-square sum")
      ->capture_default_str();
  command->add_flag("--no-parameter-sigmas", options->no_parameter_sigmas,
                    "Ignore the result's parameter uncertainty: judge against the measurement "
                    "noise alone");
  command->add_flag("--stated-camera-covariance", options->stated_camera_covariance,
                    "Judge against the camera's stated pose covariance, without the result's "
                    "camera_error_floor (the error the calibration showed beyond it)");
  command->footer(
      "Per pose: d^2 = e^T S^-1 e of the board pose error e in measurement sigmas (the dataset's "
      "sigma_t / sigma_r, else 0.2 mm / 0.03 deg) with S = D + J C J^T, C the result's "
      "parameter_covariance (its sigmas alone for an older result) and D = I plus the result's "
      "camera_error_floor (per axis, rotation and translation) in those sigmas, squared (I for "
      "an older result); chi-square(6) for an unchanged robot.");
  h4::cli::RunWhenParsed(command, options, [](const CheckCommandOptions& parsed) {
    std::string why;
    if (!parsed.check.IsValid(&why)) throw std::invalid_argument("check: " + why);
    return Run(parsed);
  });
}

}  // namespace h4::host::cli

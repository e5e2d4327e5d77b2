// `h4cal check`: does the robot still match an identification result? Reads a short
// verification campaign (a dataset CSV, e.g. 5 poses from `h4cal plan --count 5 --for-check`
// measured with `h4cal collect --plan`), compares each measured board pose with the result's
// prediction from the joints and flags the poses whose error exceeds what the measurement
// noise and the result's uncertainty allow (host/validation/drift_check.h). Exit 3 on drift.
// A corner-path result is checked on the poses measured again with its camera (--corners).
#include <stdexcept>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
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
  /// A corner-path result's check: the check's corners, their board and the camera file the
  /// poses were measured with (the poses are measured again with the result's camera).
  std::string corners_path, board_path, camera_path;
  double default_sigma_px = 0.1;  ///< as identify's --corner-sigma
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

/// The check's poses as the result's were measured (issue 42, defect 7): a corner-path
/// result's kinematics were identified on poses measured again with its refined camera, so
/// the check's are measured again with it from their corners; without corners such a result
/// is refused, saying what to give. A pose-path result takes the poses as they are.
std::vector<DatasetRow> PosesLikeTheResults(const CheckCommandOptions& o,
                                            const IdentificationResult& result,
                                            std::vector<DatasetRow> rows) {
  const int given = static_cast<int>(!o.corners_path.empty()) +
                    static_cast<int>(!o.board_path.empty()) +
                    static_cast<int>(!o.camera_path.empty());
  if (given != 0 && given != 3) {
    throw std::invalid_argument("--corners, --board and --camera go together");
  }
  if (!result.camera) {
    if (given == 3) {
      throw std::invalid_argument(
          "--corners: " + o.result_path +
          " is a pose-path result (no camera key): its poses were measured with the camera "
          "file, as the check's are; leave out --corners, --board and --camera");
    }
    return rows;
  }
  if (given == 0) {
    throw std::invalid_argument(
        o.result_path +
        " is a corner-path result (identify --corners): its kinematics were identified on poses "
        "measured again with its refined camera, not with the camera file the check's poses "
        "were measured with. Give the check's corners with --corners (collect writes them "
        "beside the dataset), --board and --camera (the camera file), so that they are measured "
        "again the same way; or check against the pose-path result");
  }
  std::vector<int64_t> dropped;
  rows = RemeasuredWithResultCamera(result, rows, ReadCornersCsv(o.corners_path),
                                    BoardModel(ReadBoardYaml(o.board_path)),
                                    ReadCameraYaml(o.camera_path), o.default_sigma_px, &dropped);
  fmt::print("check: {} poses measured again from their corners with the result's camera{}\n",
             rows.size(),
             dropped.empty() ? ""
                             : fmt::format(" ({} without enough corners left out: pose {})",
                                           dropped.size(), fmt::join(dropped, ", ")));
  return rows;
}

int Run(const CheckCommandOptions& o) {
  const IdentificationResult result = ReadIdentificationResult(o.result_path);
  const Assembly assembly =
      o.robot_path.empty() ? Assembly{} : ReadRobotYaml(o.robot_path).assembly;
  const std::vector<DatasetRow> rows = PosesLikeTheResults(o, result, ReadDatasetCsv(o.data_path));
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
  h4::cli::AddInputFileOption(
      command, "--corners", &options->corners_path,
      "A corner-path result (with a camera key): the check's corners CSV (collect writes it "
      "beside the dataset); the poses are measured again from them with the result's camera, "
      "as its kinematics were identified (needs --board and --camera)");
  h4::cli::AddBoardOption(command, &options->board_path);
  h4::cli::AddCameraOption(command, &options->camera_path,
                           "The camera file the check's poses were measured with (with --corners)");
  h4::cli::AddOptionShowingDefault(command, "--corner-sigma", &options->default_sigma_px,
                                   "Per-axis sigma (px) of corners without a sigma_px column",
                                   CLI::PositiveNumber);
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

// `h4cal fk`: forward kinematics of joint readings
// (common/formats/README.md#joints-csv-and-poses-csv-for-h4cal-fk--h4cal-ik): the end-effector pose
// in B (a Model 31's mapped from B31, robot_source.h RobotInB) and the board pose X_CT = inv(X_BC)
// X_BE inv(X_TE) it implies. With --compare, the board poses are scored against reference ones
// (e.g. a simulation's truth): the figure of issue "Host solver".
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/file_output.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/cli/robot_source.h"
#include "host/formats/joints_csv.h"
#include "host/formats/poses_csv.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host::cli {
namespace {

struct FkCommandOptions {
  RobotSourceOptions robot;
  std::string joints_path;
  std::string out_path;
  std::string compare_path;
};

void Compare(const std::vector<FkRow>& predicted, const std::string& reference_path) {
  std::map<int64_t, RigidTransform> reference;
  for (const FkRow& row : ReadFkCsv(reference_path)) reference[row.pose.pose_id] = row.X_CT;
  double sum_p2 = 0.0, sum_r2 = 0.0;
  int n = 0;
  for (const FkRow& row : predicted) {
    const auto it = reference.find(row.pose.pose_id);
    if (it == reference.end()) continue;
    const auto e = PoseError(it->second, row.X_CT);
    sum_r2 += e.head<3>().squaredNorm();
    sum_p2 += e.tail<3>().squaredNorm();
    ++n;
  }
  if (n == 0) {
    throw std::runtime_error(reference_path + ": no pose_id in common with the predicted poses");
  }
  // RMS of the 3-D error norms: position in mm, rotation angle in deg.
  fmt::print(
      "board pose error vs {} over {} poses: position RMS {:.4f} mm, rotation RMS {:.4f} deg\n",
      reference_path, n, 1e3 * std::sqrt(sum_p2 / n), DegreesFromRadians(std::sqrt(sum_r2 / n)));
}

int Run(const FkCommandOptions& options) {
  RequireOutputIsNotAnInput({"--out", options.out_path},
                            {{"--joints", options.joints_path},
                             {"--compare", options.compare_path},
                             {"--result", options.robot.result_path},
                             {"--robot", options.robot.robot_path},
                             {"--assembly-from", options.robot.assembly_robot_path}});
  std::string description;
  const RobotInB in_b = LoadRobotInB(options.robot, &description);
  const IdentifiedRobot& robot = in_b.robot;
  const std::vector<JointsRow> joints = ReadJointsCsv(options.joints_path);
  std::vector<FkRow> rows;
  std::vector<int64_t> failed;
  std::optional<EePose> guess;
  for (const JointsRow& j : joints) {
    const JointVector q(j.q[0], j.q[1], j.q[2], j.q[3]);
    FkResult fk = ForwardKinematics(*robot.model, q, guess);
    if (!fk.ok() && guess) fk = ForwardKinematics(*robot.model, q);  // from the centre
    if (!fk.ok()) {
      spdlog::warn("{}: pose_id {}: forward kinematics failed ({}): {}", options.joints_path,
                   j.pose_id, ToString(fk.status), fk.message);
      failed.push_back(j.pose_id);
      continue;
    }
    guess = fk.x;  // neighbouring rows are usually close: start the next one here
    const EePose x_B = in_b.FromModelFrame(fk.x);  // X_BC is in the model's frame, as fk.x
    rows.push_back(
        {.pose = {.pose_id = j.pose_id, .X = x_B[0], .Y = x_B[1], .Z = x_B[2], .theta = x_B[3]},
         .X_CT = PredictedBoardPose(robot.X_BC, fk.x, robot.X_TE)});
  }
  WriteFkCsv(options.out_path, rows);
  spdlog::info("fk with {}: {} of {} rows written to {} (end-effector poses in B{})", description,
               rows.size(), joints.size(), options.out_path,
               in_b.X_B31B ? ", mapped from Model 31's B31" : "");
  if (!options.compare_path.empty()) Compare(rows, options.compare_path);
  return LeftOutRowsExitCode(failed.size(), "rows had no forward kinematic solution");
}

}  // namespace

void DeclareFkCommand(CLI::App* command) {
  const auto options = std::make_shared<FkCommandOptions>();
  AddRobotSourceOptions(command, &options->robot);
  h4::cli::AddInputFileOption(command, "--joints", &options->joints_path,
                              "Joints CSV: pose_id,q1,q2,q3,q4 (rad)")
      ->required();
  h4::cli::AddOutOption(command, &options->out_path,
                        "Output CSV: pose_id,X,Y,Z,theta (the end-effector pose in B, m, rad), "
                        "x,y,z,qw,qx,qy,qz (the board pose in the camera frame)");
  h4::cli::AddInputFileOption(command, "--compare", &options->compare_path,
                              "Reference board poses in the same layout (e.g. a simulation's "
                              "heldout_truth.csv): print the RMS position and rotation error");
  command->footer(
      "Rows without a solution are reported and left out (exit code 3), never written as NaN. "
      "Poses are in B, the a priori robot's base frame, for either model: a Model 31 works in "
      "B31 (origin at P_1) and its poses are mapped through X_B31B, the nominal map of the a "
      "priori Model 12 (--robot beside --result, an export's model12 block, else the a priori "
      "the result was identified from).");
  h4::cli::RunWhenParsedForExitCode(command, options, Run);
}

}  // namespace h4::host::cli

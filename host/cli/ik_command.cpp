// `h4cal ik`: closed-form inverse kinematics (paper eq. (2)) of end-effector poses
// (common/formats/README.md poses CSV, in B; a Model 31's mapped to B31, robot_source.h RobotInB)
// to joint readings; unreachable rows are reported, not NaN.
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/file_output.h"
#include "host/cli/commands.h"
#include "host/cli/robot_source.h"
#include "host/formats/joints_csv.h"
#include "host/formats/poses_csv.h"

namespace h4::host::cli {
namespace {

struct IkCommandOptions {
  RobotSourceOptions robot;
  std::string poses_path;
  std::string out_path;
};

int Run(const IkCommandOptions& options) {
  RequireOutputIsNotAnInput({"--out", options.out_path},
                            {{"--poses", options.poses_path},
                             {"--result", options.robot.result_path},
                             {"--robot", options.robot.robot_path},
                             {"--assembly-from", options.robot.assembly_robot_path}});
  std::string description;
  const RobotInB in_b = LoadRobotInB(options.robot, &description);
  const IdentifiedRobot& robot = in_b.robot;
  const std::vector<EndEffectorPoseRow> poses = ReadPosesCsv(options.poses_path);
  std::vector<JointsRow> rows;
  size_t unreachable = 0;
  for (const EndEffectorPoseRow& p : poses) {
    const IkResult ik =
        robot.model->InverseKinematics(in_b.ToModelFrame(EePose(p.X, p.Y, p.Z, p.theta)));
    if (!ik.ok()) {
      spdlog::warn("{}: pose_id {}: out of reach (leg {})", options.poses_path, p.pose_id,
                   ik.UnreachableLegNumbers());
      ++unreachable;
      continue;
    }
    rows.push_back({p.pose_id, {ik.q[0], ik.q[1], ik.q[2], ik.q[3]}});
  }
  WriteJointsCsv(options.out_path, rows);
  spdlog::info("ik with {}: {} of {} rows written to {} (targets in B{})", description, rows.size(),
               poses.size(), options.out_path, in_b.X_B31B ? ", mapped to Model 31's B31" : "");
  return LeftOutRowsExitCode(unreachable, "poses are out of reach");
}

}  // namespace

void DeclareIkCommand(CLI::App* command) {
  const auto options = std::make_shared<IkCommandOptions>();
  AddRobotSourceOptions(command, &options->robot);
  h4::cli::AddInputFileOption(command, "--poses", &options->poses_path,
                              "Poses CSV: pose_id,X,Y,Z,theta (the end-effector pose in B, m, "
                              "rad)")
      ->required();
  h4::cli::AddOutOption(command, &options->out_path, "Output joints CSV: pose_id,q1,q2,q3,q4");
  command->footer(
      "Unreachable rows are reported and left out (exit code 3). Poses are in B, the a priori "
      "robot's base frame, for either model: a Model 31 works in B31 (origin at P_1) and the "
      "targets are mapped through X_B31B, the nominal map of the a priori Model 12 (--robot "
      "beside --result, as collect --controller; an export's model12 block; else the a priori "
      "the result was identified from).");
  h4::cli::RunWhenParsedForExitCode(command, options, Run);
}

}  // namespace h4::host::cli

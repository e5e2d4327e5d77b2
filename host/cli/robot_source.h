// The robot a command works with: an identification result (--result, with --robot for its
// assembly signs, as in export and check) or a robot.yaml alone (--robot: its Model 12, or
// the model31 block of a Model 31 export), as one model with its X_BC and X_TE.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "host/identification/identified_robot.h"

namespace h4::host::cli {

struct RobotSourceOptions {
  std::string result_path;          ///< --result result.json
  std::string robot_path;           ///< --robot robot.yaml (beside --result: assembly signs)
  std::string assembly_robot_path;  ///< --assembly-from: the old spelling of --robot there
};

/// Adds --result and --robot (at least one required) to a subcommand.
void AddRobotSourceOptions(CLI::App* command, RobotSourceOptions* options);

/// A robot whose end-effector poses are given and taken in B, the frame of the poses and
/// joints CSVs (common/formats/README.md) and of `collect`'s plans: a Model 31 works in its
/// own base frame B31, so its poses go through X_B31B (issue 42, defect 8: an `ik` target of
/// a Model 31 result landed 140 mm away).
struct RobotInB {
  IdentifiedRobot robot;
  /// B -> B31 for a Model 31 (NominalX_B31B of the a priori Model 12, model31.h): of --robot
  /// beside a result, as `collect --controller` maps its plan; of the export's own model12
  /// block; else of the a priori the result was identified from, which its parameters'
  /// a priori values give (psi_i = alpha_i, x_i, y_i, d: common/README.md's nominal map).
  /// Empty for a Model 12.
  std::optional<RigidTransform> X_B31B;
  EePose ToModelFrame(const EePose& x_B) const;    ///< B -> the model's base frame
  EePose FromModelFrame(const EePose& x_M) const;  ///< the model's base frame -> B
};
RobotInB LoadRobotInB(const RobotSourceOptions& options, std::string* description);

/// Loads the robot; throws with the file's name on any problem. A --robot file with a
/// model31 block (h4cal export of a Model 31 result) is that Model 31, never its model12
/// block (the a priori the format requires beside it).
IdentifiedRobot LoadRobot(const RobotSourceOptions& options, std::string* description);

}  // namespace h4::host::cli

// The robot a command works with: an identification result (--result, with --robot for its
// assembly signs, as in export and check) or a robot.yaml alone (--robot: its Model 12, or
// the model31 block of a Model 31 export), as one model with its X_BC and X_TE.
#pragma once

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

/// Loads the robot; throws with the file's name on any problem. A --robot file with a
/// model31 block (h4cal export of a Model 31 result) is that Model 31, never its model12
/// block (the a priori the format requires beside it).
IdentifiedRobot LoadRobot(const RobotSourceOptions& options, std::string* description);

}  // namespace h4::host::cli

// The robot a command works with: an identification result (--result) or an a priori
// robot.yaml (--robot, its Model 12), as one model with its X_BC and X_TE.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "host/identification/identified_robot.h"

namespace h4::host::cli {

struct RobotSourceOptions {
  std::string result_path;          ///< --result result.json
  std::string robot_path;           ///< --robot robot.yaml
  std::string assembly_robot_path;  ///< --assembly-from robot.yaml: assembly signs for --result
};

/// Adds --result / --robot (exactly one required) to a subcommand.
void AddRobotSourceOptions(CLI::App* command, RobotSourceOptions* options);

/// Loads the robot; throws with the file's name on any problem, and refuses a --robot
/// file with a model31 block (its model12 block is not the robot it describes).
IdentifiedRobot LoadRobot(const RobotSourceOptions& options, std::string* description);

}  // namespace h4::host::cli

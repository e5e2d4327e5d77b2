// The check of a pose plan against the robot's reach, for `plan` and `collect` (issue 26):
// the poses the a priori robot.yaml's Model 12 and assembly signs do not reach, or reach
// with a joint outside --joint-range-deg, named before the robot moves.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include "host/kinematics/pose_plan.h"
#include "host/kinematics/robot_description.h"

namespace h4::host::cli {

/// --joint-range-deg MIN,MAX (empty text: no limit).
CLI::Option* AddJointRangeOption(CLI::App* command, std::string* text);
/// "MIN,MAX" in degrees as a range in rad, nullopt for ""; throws naming the option on
/// anything else.
std::optional<Eigen::Vector2d> ParseJointRange(const std::string& text);

/// The poses of `plan` out of `robot`'s reach, pose id -> why (X, Y, Z, theta and the leg or
/// joint), for the caller to name once; logs one line: every pose within reach, or how many
/// are not and how to plan within the reach (--joint-range-deg).
std::map<int64_t, std::string> CheckPlanReach(const RobotDescription& robot, const PosePlan& plan,
                                              const std::optional<Eigen::Vector2d>& joint_range);

}  // namespace h4::host::cli

// Whether the robot will take a plan's poses, decided before it moves (issue 26): a
// controller turns a pose target into joints with the a priori Model 12's inverse
// kinematics and its assembly signs (robot.yaml), and refuses a pose out of that reach or
// past its joint limits. The same computation here names those poses by id, so that `collect
// --plan` does not send them and `plan` never chooses them (CandidateFilter uses it too).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/pose_plan.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// Why a robot refuses a pose target, before any camera consideration.
enum class ReachVerdict { kOk, kUnreachable, kJointRange };

struct ReachResult {
  ReachVerdict verdict = ReachVerdict::kUnreachable;
  JointVector q = JointVector::Zero();  ///< the inverse kinematics' joints (when not kUnreachable)
  std::string why;                      ///< which leg or joint, for the operator ("" when kOk)
};

/// `model`'s inverse kinematics at x_B (in B), and every joint within `joint_range` (rad;
/// unset: any angle).
ReachResult CheckReach(const KinematicModel& model, const EePose& x_B,
                       const std::optional<Eigen::Vector2d>& joint_range);

struct UnreachablePose {
  int64_t pose_id = 0;
  EePose x = EePose::Zero();
  std::string why;
};

/// The poses of `plan` the a priori Model 12 of `robot` (with its assembly signs) does not
/// reach within `joint_range`, in plan order.
std::vector<UnreachablePose> UnreachablePoses(const RobotDescription& robot, const PosePlan& plan,
                                              const std::optional<Eigen::Vector2d>& joint_range);

/// "pose 18 (X 250.0, Y -250.0, Z -600.0 mm, theta 60.0 deg): leg 2 has no inverse
/// kinematics".
std::string Describe(const UnreachablePose& pose);

}  // namespace h4::host

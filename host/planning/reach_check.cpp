// Whether the robot will take a plan's poses; see reach_check.h.
#include "host/planning/reach_check.h"

#include <algorithm>

#include <spdlog/fmt/fmt.h>

#include "common/units.h"
#include "host/kinematics/model12.h"

namespace h4::host {
namespace {

// "leg 2" or "legs 1, 3": the legs whose closed-form inverse kinematics has no solution.
std::string UnreachableLegs(const IkResult& ik) {
  const auto count = std::count(ik.reachable.begin(), ik.reachable.end(), false);
  return (count > 1 ? "legs " : "leg ") + ik.UnreachableLegNumbers();
}

}  // namespace

ReachResult CheckReach(const KinematicModel& model, const EePose& x_B,
                       const std::optional<Eigen::Vector2d>& joint_range) {
  ReachResult result;
  const IkResult ik = model.InverseKinematics(x_B);
  if (!ik.ok()) {
    result.why = UnreachableLegs(ik) + " out of reach (no inverse kinematics)";
    return result;
  }
  result.q = ik.q;
  for (int i = 0; joint_range && i < 4; ++i) {
    const Eigen::Vector2d& range = *joint_range;
    if (ik.q[i] < range[0] || ik.q[i] > range[1]) {
      result.verdict = ReachVerdict::kJointRange;
      result.why = fmt::format("joint {} at {:.1f} deg, outside the joint range {:.1f}..{:.1f} deg",
                               i + 1, DegreesFromRadians(ik.q[i]), DegreesFromRadians(range[0]),
                               DegreesFromRadians(range[1]));
      return result;
    }
  }
  result.verdict = ReachVerdict::kOk;
  return result;
}

std::vector<UnreachablePose> UnreachablePoses(const RobotDescription& robot, const PosePlan& plan,
                                              const std::optional<Eigen::Vector2d>& joint_range) {
  const Model12 model(robot.model12, robot.assembly);
  std::vector<UnreachablePose> unreachable;
  for (const PlannedPose& pose : plan) {
    const ReachResult reach = CheckReach(model, pose.x, joint_range);
    if (reach.verdict != ReachVerdict::kOk) {
      unreachable.push_back({pose.pose_id, pose.x, reach.why});
    }
  }
  return unreachable;
}

std::string Describe(const UnreachablePose& pose) {
  return fmt::format("pose {} (X {:.1f}, Y {:.1f}, Z {:.1f} mm, theta {:.1f} deg): {}",
                     pose.pose_id, pose.x[0] * 1e3, pose.x[1] * 1e3, pose.x[2] * 1e3,
                     DegreesFromRadians(pose.x[3]), pose.why);
}

}  // namespace h4::host

// The check of a pose plan against the robot's reach; see plan_reach.h.
#include "host/cli/plan_reach.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "common/units.h"
#include "host/planning/reach_check.h"

namespace h4::host::cli {

CLI::Option* AddJointRangeOption(CLI::App* command, std::string* text) {
  return command->add_option(
      "--joint-range-deg", *text,
      "MIN,MAX joint range (encoder values, deg) every joint must stay in (the controller's "
      "joint limits)");
}

std::optional<Eigen::Vector2d> ParseJointRange(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double low = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != ',') {
    throw std::invalid_argument("--joint-range-deg \"" + text + "\": expected MIN,MAX in degrees");
  }
  const char* at = end + 1;
  const double high = std::strtod(at, &end);
  if (end == at || *end != '\0' || !(low < high) || !std::isfinite(low) || !std::isfinite(high)) {
    throw std::invalid_argument("--joint-range-deg \"" + text +
                                "\": expected MIN,MAX in degrees with MIN < MAX");
  }
  return Eigen::Vector2d(RadiansFromDegrees(low), RadiansFromDegrees(high));
}

std::map<int64_t, std::string> CheckPlanReach(const RobotDescription& robot, const PosePlan& plan,
                                              const std::optional<Eigen::Vector2d>& joint_range) {
  std::map<int64_t, std::string> unreachable;
  for (const UnreachablePose& pose : UnreachablePoses(robot, plan, joint_range)) {
    unreachable[pose.pose_id] = Describe(pose);
  }
  const std::string limits = joint_range ? fmt::format(" with every joint in {:.1f}..{:.1f} deg",
                                                       DegreesFromRadians((*joint_range)[0]),
                                                       DegreesFromRadians((*joint_range)[1]))
                                         : " (no joint range given: --joint-range-deg)";
  if (unreachable.empty()) {
    spdlog::info("every one of the {} planned poses is within the a priori robot's reach{}",
                 plan.size(), limits);
  } else {
    spdlog::warn(
        "{} of the {} planned poses are out of the a priori robot's reach{}: plan again within "
        "it (h4cal plan --robot ... --joint-range-deg MIN,MAX, the controller's joint limits)",
        unreachable.size(), plan.size(), limits);
  }
  return unreachable;
}

}  // namespace h4::host::cli

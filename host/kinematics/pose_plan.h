// Pose plans: the end-effector poses a campaign or a simulation visits, independent of how
// they were loaded (the poses CSV: host/formats/pose_plan_rows.h) or generated (a planner,
// host/planning), and the paper's 81-pose grid, the plan every other is compared with.
#pragma once

#include <cstdint>
#include <vector>

#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct PlannedPose {
  int64_t pose_id = 0;
  EePose x = EePose::Zero();  ///< X_BE in Model 12's base B, m and rad
};
using PosePlan = std::vector<PlannedPose>;

struct GridOptions {
  EePose centre = EePose(0.0, 0.0, -0.45, 0.0);  ///< grid centre in B (theta ignored)
  Eigen::Vector3d size = Eigen::Vector3d(0.200, 0.200, 0.150);  ///< full extent along x, y, z, m
  int positions_per_axis = 3;                                   ///< 3 x 3 x 3 positions
  std::vector<double> theta = {-0.3490658503988659, 0.0, 0.3490658503988659};  ///< rad (+-20 deg)
  int64_t first_pose_id = 1;
};

/// The paper's grid (defaults: 200 x 200 x 150 mm centred at (0, 0, -0.45) m, 3 x 3 x 3
/// positions, theta in {-20, 0, 20} deg: 81 poses). Order: z, then y, then x, then theta
/// vary slowest to fastest; pose ids count up from first_pose_id.
PosePlan GridPosePlan(const GridOptions& options = GridOptions{});

}  // namespace h4::host

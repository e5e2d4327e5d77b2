// Pose plans; see pose_plan.h.
#include "host/kinematics/pose_plan.h"

namespace h4::host {

PosePlan GridPosePlan(const GridOptions& options) {
  PosePlan plan;
  const int n = options.positions_per_axis;
  auto coordinate = [&](int axis, int k) {
    if (n <= 1) return options.centre[axis];
    return options.centre[axis] + options.size[axis] * (static_cast<double>(k) / (n - 1) - 0.5);
  };
  int64_t id = options.first_pose_id;
  for (int iz = 0; iz < n; ++iz) {
    for (int iy = 0; iy < n; ++iy) {
      for (int ix = 0; ix < n; ++ix) {
        for (double theta : options.theta) {
          plan.push_back(
              {id++, EePose(coordinate(0, ix), coordinate(1, iy), coordinate(2, iz), theta)});
        }
      }
    }
  }
  return plan;
}

}  // namespace h4::host

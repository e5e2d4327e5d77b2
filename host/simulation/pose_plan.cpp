// Pose plans; see pose_plan.h.
#include "host/simulation/pose_plan.h"

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

PosePlan PosePlanFromRows(const std::vector<EndEffectorPoseRow>& rows) {
  PosePlan plan;
  plan.reserve(rows.size());
  for (const auto& row : rows)
    plan.push_back({row.pose_id, EePose(row.X, row.Y, row.Z, row.theta)});
  return plan;
}

std::vector<EndEffectorPoseRow> RowsFromPosePlan(const PosePlan& plan) {
  std::vector<EndEffectorPoseRow> rows;
  rows.reserve(plan.size());
  for (const auto& pose : plan) {
    rows.push_back({pose.pose_id, pose.x[0], pose.x[1], pose.x[2], pose.x[3]});
  }
  return rows;
}

}  // namespace h4::host

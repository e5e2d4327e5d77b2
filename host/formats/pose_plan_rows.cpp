// A pose plan to and from the poses CSV's rows; see pose_plan_rows.h.
#include "host/formats/pose_plan_rows.h"

namespace h4::host {

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

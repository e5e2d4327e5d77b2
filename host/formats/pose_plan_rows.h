// A pose plan (host/kinematics/pose_plan.h) to and from the rows of the poses CSV
// (common/formats/README.md).
#pragma once

#include <vector>

#include "host/formats/poses_csv.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host {

PosePlan PosePlanFromRows(const std::vector<EndEffectorPoseRow>& rows);
std::vector<EndEffectorPoseRow> RowsFromPosePlan(const PosePlan& plan);

}  // namespace h4::host

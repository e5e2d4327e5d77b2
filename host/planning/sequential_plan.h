// The second stage of a sequential campaign (`h4cal plan --from result.json --existing
// dataset.csv`): the rest of the poses is planned on the robot the first batch identified,
// not on the a priori, and completes the poses measured already. Here: that robot as a
// description, and the poses the first batch was measured at.
#pragma once

#include <vector>

#include "common/formats/dataset_csv.h"
#include "common/formats/identification_result.h"
#include "common/robot/robot_description.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// `apriori` (robot.yaml: its model12 defines B, and its assembly signs) with the result's
/// identified model (a Model 31 result as the model31 block, a Model 12 result as model12),
/// and its X_BC and X_TE moved to B (a Model 31 result's X_BC is in B31,
/// common/README.md). Throws std::invalid_argument as RebuildFromResult does.
RobotDescription IdentifiedDescription(const RobotDescription& apriori,
                                       const IdentificationResult& result);

/// The end-effector poses in B the rows were measured at, as their boards show them through
/// `robot`'s placement: X_BE = X_BC X_CT X_TE (eq. (6)), without the tilt an H4 cannot take.
std::vector<EePose> MeasuredPoses(const RobotDescription& robot,
                                  const std::vector<DatasetRow>& rows);

}  // namespace h4::host

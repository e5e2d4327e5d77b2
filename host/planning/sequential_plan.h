// A sequential campaign (`h4cal collect --sequential FIRST,TOTAL`; by hand `h4cal plan`, then
// `h4cal plan --from result.json --existing dataset.csv`): a first batch planned on the a
// priori robot inside the target region, measured and identified; the rest planned on the
// robot the first batch identified, not on the a priori, completing the poses measured
// already (docs/results.md#planned-poses-on-robots-the-planner-has-never-seen). Here: each
// stage's planning problem, that robot as a description, and the poses the first batch was
// measured at.
#pragma once

#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"
#include "host/planning/pose_planner.h"

namespace h4::host {

/// The first stage plans among candidates inside the target region only: poses a camera set
/// up centimetres and degrees from robot.yaml's X_BC still sees whole, so that the first
/// batch identifies the robot and its camera before wider poses are chosen.
PlanningProblemOptions FirstStageOptions(PlanningProblemOptions options);

/// The next stage plans on `identified` (IdentifiedDescription), completing `measured`, and
/// on it alone: draws spread as an a priori's would plan for an uncertainty the first batch
/// has removed. Keeping them to leave out the candidates one of them misses lost accuracy
/// (20 + 51 poses, 20 robots per prior: median ratio to the grid 0.77 and 0.70, worst 1.75
/// and 1.54, against 0.67 and 0.70, worst 1.18 and 1.18 without;
/// docs/results.md#planned-poses-on-robots-the-planner-has-never-seen). A pose out of the
/// true robot's reach is refused at once and skipped (live, after a 12-pose first stage: 0
/// to 4 of 12 second-stage poses, run to run).
PlanningProblemOptions NextStageOptions(PlanningProblemOptions options,
                                        const RobotDescription& identified,
                                        const std::vector<DatasetRow>& measured);

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

// The stages of a sequential campaign (sequential_plan.h).
#include "host/planning/sequential_plan.h"

#include "common/units.h"
#include "host/identification/identified_robot.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host {

PlanningProblemOptions FirstStageOptions(PlanningProblemOptions options) {
  options.candidates.centre = options.target.centre;
  options.candidates.half_extent = options.target.half_extent;
  options.candidates.theta.clear();
  // The candidates' theta step (CandidateOptions::theta), over the region's range.
  const double step = RadiansFromDegrees(10.0);
  for (double t = options.target.theta_min; t <= options.target.theta_max + 1e-9; t += step) {
    options.candidates.theta.push_back(t);
  }
  return options;
}

PlanningProblemOptions NextStageOptions(PlanningProblemOptions options,
                                        const RobotDescription& identified,
                                        const std::vector<DatasetRow>& measured) {
  options.existing_poses_B = MeasuredPoses(identified, measured);
  options.robust.robots = 0;
  return options;
}

RobotDescription IdentifiedDescription(const RobotDescription& apriori,
                                       const IdentificationResult& result) {
  const IdentifiedRobot identified = RebuildFromResult(result, apriori.assembly);
  RobotDescription robot = apriori;
  robot.X_TE = identified.X_TE;
  if (const auto* model31 = dynamic_cast<const Model31*>(identified.model.get())) {
    robot.model31 = model31->model31_parameters();
    // B is the a priori's, as the plan's poses are.
    robot.X_BC = CameraInPlanFrame(result, apriori.model12);
  } else {
    robot.model12 = dynamic_cast<const Model12&>(*identified.model).model12_parameters();
    robot.model31.reset();
    robot.X_BC = identified.X_BC;
  }
  return robot;
}

std::vector<EePose> MeasuredPoses(const RobotDescription& robot,
                                  const std::vector<DatasetRow>& rows) {
  std::vector<EePose> poses_B;
  for (const DatasetRow& row : rows) {
    poses_B.push_back(EePoseFromMeasurement(robot.X_BC, row.X_CT, robot.X_TE).x);
  }
  return poses_B;
}

}  // namespace h4::host

// The figures the verdict (verdict.h) is decided from, gathered at an identification's
// solution: the chi-square of the measurement-space residuals (board poses normalised by
// their covariance, whatever the estimator was), the board position misfit, the poses out
// of reach, and how far the kinematic parameters moved from the a priori robot.
#pragma once

#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/uncertainty.h"
#include "host/identification/verdict.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct SolutionToJudge {
  const KinematicModel& model;
  const ParameterVector& apriori;  ///< the robot.yaml values
  const ParameterVector& p;        ///< the solution with its mask
  const std::vector<DatasetRow>& in_fit;
  int poses_given = 0;
  int poses_rejected = 0;
  bool converged = false;
  const Uncertainty& uncertainty;
  const CostOptions& cost;
};

VerdictInputs GatherVerdictInputs(const SolutionToJudge& solution);

}  // namespace h4::host

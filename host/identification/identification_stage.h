// One stage of the identification (identification.h): a cost minimised from the current
// parameters, after the identifiability analysis at its start point has fixed what the
// poses cannot see. The steps, top-down: set the stage's mask, evaluate at the start,
// analyse identifiability, minimise (NLopt, then the Levenberg-Marquardt polish),
// evaluate at the solution.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/formats/dataset_csv.h"
#include "host/identification/identifiability.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct IdentificationOptions;
struct StageSummary;

/// One planned stage: the cost, and whether the kinematics are held at their values so
/// that only X_BC and X_TE move (the placement stage).
struct PlannedStage {
  CostKind cost = CostKind::kImplicit;
  bool placement_only = false;
};

/// The options' stages in order: the warm-up costs, then the estimator, the first one
/// preceded by its placement stage when options.placement_first.
std::vector<PlannedStage> PlanStages(const IdentificationOptions& options);

/// What every stage of one identification reads. `reference` holds the values a parameter
/// fixed by the analysis takes (the start: the a priori after the prior analysis, or the
/// --from result; common/README.md#identification).
struct StageContext {
  const KinematicModel& model;
  const IdentificationOptions& options;
  const ParameterVector& reference;
};

/// The estimator's residuals and Jacobian (by all parameters) at the final parameters on
/// the calibration poses: computed once by the last stage, used for the outlier check, the
/// covariance and the predicted accuracy.
struct SolutionJacobian {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
};

/// What the final stage also hands back: its identifiability analysis and its solution.
struct FinalStageOutputs {
  IdentifiabilityReport identifiability;
  SolutionJacobian solution;
};

/// Runs `stage` on `rows`: `p` carries the values in and out, and its mask on return is
/// this stage's. `final_outputs` (may be null) receives the analysis and the solution.
StageSummary RunStage(const StageContext& context, const PlannedStage& stage,
                      const std::vector<DatasetRow>& rows, ParameterVector* p,
                      FinalStageOutputs* final_outputs);

/// One log line per stage: what ran, how many iterations and evaluations, the costs.
std::string StageLogLine(const StageSummary& stage);

/// The calibration rows made exactly consistent with the parameters p (joints by IK of the
/// measured poses, X_CT re-predicted without the measured tilt): the rows on which the
/// identifiability analysis is done, so that noise does not hide exact null directions.
std::vector<DatasetRow> ConsistentRows(const KinematicModel& model, const ParameterVector& p,
                                       const std::vector<DatasetRow>& rows);

}  // namespace h4::host

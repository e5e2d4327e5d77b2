// Filling the IdentificationResult of an identification (common/formats/README.md): parameters with a
// priori values, standard deviations and status, fixed parameters with reasons, joint
// residuals, held-out board pose error, covariance figures and the log.
#pragma once

#include <cstdint>
#include <vector>

#include "host/identification/identification.h"

namespace h4::host {

/// The estimator's residuals and Jacobian (by all parameters) at the final parameters on
/// the calibration poses, when the last stage already has them: computed once, used for
/// the covariance and the predicted accuracy.
struct SolutionJacobian {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
};

/// Fills out->result and out->uncertainty for the final parameters `p` (with their mask),
/// `calib` the poses used (rejected ones removed), `valid` the held-out poses. `at_solution`
/// (may be null: evaluated here) must be the estimator's cost at p on exactly `calib`.
void FillResult(const KinematicModel& model, const ParameterVector& apriori,
                const ParameterVector& p, const std::vector<DatasetRow>& calib,
                const std::vector<DatasetRow>& valid, const std::vector<int64_t>& rejected,
                const IdentificationOptions& options, IdentificationOutcome* out,
                const SolutionJacobian* at_solution = nullptr);

}  // namespace h4::host

// Uncertainty of identified parameters: the covariance at the solution from the Jacobian of
// the free parameters, sigma^2 (J^T J)^-1 with the residual variance sigma^2 for the
// unweighted costs (eq. (3), eq. (5)), (J^T J)^-1 for the measurement-space cost whose
// residuals are already divided by their standard deviations, scaled by chi2/dof when that
// exceeds 1 (misfit beyond the sigmas: the uncertainty includes it); one-sigma per parameter
// and strongly correlated pairs.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/formats/identification_result.h"
#include "host/identification/parameter_vector.h"

namespace h4::host {

struct Uncertainty {
  bool ok = false;
  std::vector<int> free_indices;  ///< parameter indices of the rows/columns below
  Eigen::MatrixXd covariance;     ///< of the free parameters, SI units squared
  Eigen::VectorXd std;            ///< one sigma per free parameter
  double chi2_per_dof = 0.0;      ///< |r|^2 / (residuals - free parameters)
  double sigma2 = 1.0;  ///< scales the covariance: chi2/dof, or max(1, chi2/dof) if weighted
  double condition_number = 0.0;             ///< of the column-scaled Jacobian
  std::vector<CorrelatedPair> correlations;  ///< |rho| above the threshold, largest first
};

/// r, J_full: residuals and Jacobian by all parameters at the solution. `weighted`: the
/// residuals are divided by their standard deviations (measurement cost).
Uncertainty ComputeUncertainty(const ParameterVector& p, const Eigen::VectorXd& r,
                               const Eigen::MatrixXd& J_full, bool weighted,
                               double correlation_threshold = 0.9);

/// RMS over the rows of J_point (3 rows per point, by all parameters) of the one-sigma
/// position error sqrt(trace(J C J^T)), m: the position accuracy the covariance predicts.
double PredictedPositionAccuracy(const Uncertainty& u, const Eigen::MatrixXd& J_point_full);

}  // namespace h4::host

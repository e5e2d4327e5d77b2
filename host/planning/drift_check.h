// Whether a robot still matches an identification result (`h4cal check`): a short
// verification campaign (a few poses) is compared with what the result predicts. Each
// pose's board pose error e (the measurement-space residual of the identification,
// identification_cost.h, in units of the measurement sigmas) is judged against its
// covariance S = I + J D J^T, where D holds the result's one-sigma parameter uncertainties
// (the result file keeps no correlations, so D is diagonal: a conservative spread). Under
// an unchanged robot d^2 = e^T S^-1 e is chi-square with 6 degrees of freedom per pose and
// their sum chi-square with 6 n; a pose is flagged above the per-pose quantile (Bonferroni
// over the poses), and the robot has drifted when a pose is flagged or the sum exceeds its
// quantile.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/formats/dataset_csv.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"

namespace h4::host {

struct DriftCheckOptions {
  /// Probability that an unchanged robot has some pose flagged (shared over the poses).
  double pose_false_alarm = 0.01;
  /// Probability that an unchanged robot fails the sum test.
  double total_false_alarm = 0.02;
  CostOptions cost;  ///< sigmas of rows without their own

  bool IsValid(std::string* why) const;
};

struct PoseCheck {
  int64_t pose_id = 0;
  double mahalanobis2 = 0.0;    ///< d^2, chi-square(6) under an unchanged robot
  double position_error = 0.0;  ///< |translation error| in C, m
  double rotation_error = 0.0;  ///< |rotation error|, rad
  bool flagged = false;
};

struct DriftCheckResult {
  std::vector<PoseCheck> poses;
  double chi2 = 0.0;            ///< sum of d^2
  int dof = 0;                  ///< 6 per pose
  double pose_threshold = 0.0;  ///< d^2 above this flags a pose
  double total_threshold = 0.0;
  bool evaluable = true;  ///< false: a pose could not be evaluated (why in message)
  bool drift = false;
  std::string message;
  std::string Summary() const;
};

/// p: the result's parameters (fixed ones marked fixed); parameter_std: one sigma per
/// parameter of p (0 for fixed ones); `model` gives the model kind. Throws
/// std::invalid_argument on invalid options, empty rows or a std vector of the wrong size.
DriftCheckResult CheckForDrift(const KinematicModel& model, const ParameterVector& p,
                               const Eigen::VectorXd& parameter_std,
                               const std::vector<DatasetRow>& rows,
                               const DriftCheckOptions& options = DriftCheckOptions{});

/// Upper tail quantile of chi-square with an even number of degrees of freedom: the x with
/// P(X > x) = tail_probability.
double ChiSquareUpperQuantileEvenDof(int dof, double tail_probability);

}  // namespace h4::host

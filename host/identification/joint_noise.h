// Encoder noise seen in the corner residuals. The corner cost weighs each corner by its own
// pixel noise as if the joint readings were exact; a reading's noise instead moves all the
// corners of its pose together (the pose's 4 columns G_j = dr_j/dq_j), a noise that does not
// average out over a pose's 144 corners. Left out, the covariance (J^T J)^-1 claims the
// corner noise floor; measured on simulated robots with 2e-5 rad encoders, the true accuracy
// was 1.5-2.3x the predicted one (docs/results.md#when-the-camera-file-is-wrong-the-corner-path).
//
// The residual covariance is modelled as s2 I + sigma_q^2 blockdiag(G_j G_j^T) (weighted
// units) and its two scales are estimated from the residuals split into their part in each
// pose's joint directions (P_j = G_j (G_j^T G_j)^-1 G_j^T) and the rest, with the expectations
// of both parts after the fit's projection I - H, H = J A^-1 J^T, A = J^T J:
//   E|P r|^2       = s2 (4N - tr(A^-1 K)) + sigma_q^2 (tr B - 2 tr(A^-1 M) + tr(A^-1 K A^-1 M))
//   E|(I - P) r|^2 = s2 (m - 4N - n + tr(A^-1 K)) + sigma_q^2 (tr(A^-1 M) - tr(A^-1 K A^-1 M))
// with K = sum_j J_j^T P_j J_j, M = sum_j J_j^T G_j G_j^T J_j, tr B = sum_j tr(G_j^T G_j).
// The covariance of the (unchanged) estimate is then the sandwich
//   C = max(1, s2) A^-1 + sigma_q^2 A^-1 M A^-1.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "host/identification/parameter_vector.h"
#include "host/identification/uncertainty.h"

namespace h4::host {

/// One pose's rows in the residual vector and the residuals' derivative by its joint readings.
struct PoseJointColumns {
  Eigen::Index offset = 0;
  Eigen::Matrix<double, Eigen::Dynamic, 4> G;  ///< weighted residual by q_1..q_4, rad^-1
};

struct JointNoise {
  bool estimated = false;   ///< false: too few residuals, or u had no covariance
  double sigma_q = 0.0;     ///< encoder noise per joint reading, rad (one sigma)
  double pixel_scale2 = 1;  ///< s2: the corner noise's variance over the one assumed
};

/// Estimates the joint noise from the residuals r and Jacobian J_full (by all parameters) at
/// a weighted fit's solution, and widens u's covariance, std and predicted figures with it.
JointNoise AddJointNoise(const ParameterVector& p, const Eigen::VectorXd& r,
                         const Eigen::MatrixXd& J_full,
                         const std::vector<PoseJointColumns>& poses, Uncertainty* u);

}  // namespace h4::host

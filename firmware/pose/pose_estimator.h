// Board pose X_CT from its corners in one image: planar PnP. Both IPPE solutions (on
// undistorted points) start a Levenberg-Marquardt refinement of the pixel reprojection
// error through the full distortion model; the one with the lower error wins (the planar
// ambiguity). The covariance of the fit, sigma^2 (J^T J)^-1 with sigma^2 from the
// residuals, is in the order of messages/README.md: translation p_CT in C (m), then the
// rotation vector (rad) of the right perturbation R_CT * Exp(delta), delta in T.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/detection/corner_observation.h"

namespace h4::cam {

struct PoseOptions {
  int max_iterations = 50;        ///< LM iterations per start
  double step_tolerance = 1e-12;  ///< stop when the update is below this (m and rad)
  int min_corners = 4;            ///< fewer: status kTooFewCorners
};

struct PoseEstimate {
  enum class Status { kOk, kTooFewCorners, kFailed };
  Status status = Status::kFailed;
  std::string message;  ///< why, when not ok
  RigidTransform X_CT;
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double rms_px = 0;   ///< RMS reprojection error (over the 2N coordinates)
  double sigma_t = 0;  ///< sqrt(trace(cov_tt) / 3): per-axis position sigma, m
  double sigma_r = 0;  ///< sqrt(trace(cov_rr) / 3): per-axis rotation sigma, rad
  int corners = 0;     ///< corners used
  int iterations = 0;  ///< LM iterations of the kept solution
  /// RMS of the other planar solution after refinement (px); +inf when IPPE gave one.
  /// Close to rms_px means the ambiguity was weakly resolved.
  double alternative_rms_px = 0;
  bool ok() const { return status == Status::kOk; }
};

PoseEstimate EstimatePose(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                          const PoseOptions& options = {});

/// Residuals r = project(X_CT * p_TQ) - uv (2N) and, when J is given, their Jacobian
/// (2N x 6) w.r.t. (delta_t in C, delta_r right perturbation in T). False when a point is
/// behind the camera.
bool ReprojectionResiduals(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                           const RigidTransform& X_CT, Eigen::VectorXd* r,
                           Eigen::MatrixXd* J = nullptr);

}  // namespace h4::cam

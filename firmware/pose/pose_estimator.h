// Board pose X_CT from its corners in one image: planar PnP. Both IPPE solutions (on
// undistorted points) start a Levenberg-Marquardt refinement of the pixel reprojection
// error through the full distortion model; the one with the lower error wins (the planar
// ambiguity). The covariance of the fit (CovarianceModel: the edge fits' noise propagated
// through the corners by default, else from the residuals) is in the order of
// messages/README.md: translation p_CT in C (m), then the rotation vector (rad) of the
// right perturbation R_CT * Exp(delta), delta in T.
//
// Erosion: under blur, a non-linear (gamma-encoded) response moves every edge of a dark
// tag toward its dark side, so all tags of a grid look uniformly eroded and the board
// looks smaller, which a plain fit turns into a depth error. When the corners carry their
// erosion directions (corner_observation.h), the fit adds the erosion (px) as nuisance
// parameters, uv = project(X_CT p_TQ) + e(uv) * erosion_px, and reports the pose's
// marginal covariance: the erosion and the depth are told apart by the tag spacing, which
// erosion does not change.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/detection/corner_observation.h"

namespace h4::cam {

/// How the erosion of dark features (corner_observation.h) enters the pose fit.
enum class ErosionModel {
  kNone,    ///< corners taken as they are
  kGlobal,  ///< one erosion for the whole image (blur and response uniform)
  kAffine,  ///< erosion varying affinely across the image (blur changing with defocus)
  kPerTag,  ///< one erosion per edge group (tag): also takes each tag's own size bias
};

/// How the pose covariance is estimated from the fit (pose_estimator.cpp says why).
enum class CovarianceModel {
  kResidual,   ///< sigma^2 (J^T J)^-1, corners independent, sigma^2 from the residuals
  kEdgeGroup,  ///< cluster-robust: residuals of one edge group (a tag) taken as correlated
  /// The edge fits' pixel noise propagated through the corners (CornerNoisePx, correlated
  /// within a tag), plus the residuals' excess over what that noise explains, taken as
  /// independent per corner; kResidual where no corner carries its noise.
  kEdgeNoise,
};

struct PoseOptions {
  int max_iterations = 50;        ///< LM iterations per start
  double step_tolerance = 1e-12;  ///< stop when the update is below this (m, rad and px)
  int min_corners = 4;            ///< fewer: status kTooFewCorners
  /// Erosion parameters fitted when corners carry erosion directions (kAffine: blur, hence
  /// erosion, changes over a tilted board; measured against kGlobal and kPerTag with
  /// firmware/bench/measure_response, it cut the rotation error under 1.4 px blur from
  /// 0.008 to 0.005 deg over 8 scenes for two more parameters); the pose is fitted without them
  /// when fewer than `min_erosion_corners` corners carry one (a single tag cannot tell its erosion
  /// from its depth).
  ErosionModel erosion = ErosionModel::kAffine;
  int min_erosion_corners = 8;
  /// kEdgeNoise: the corners of a tag share the noise of its four fitted sides, which moves
  /// them in ways the pose hardly feels; kResidual takes them as independent and reported
  /// up to 2.5x the actual error on clean renders (measurements in the README's vision
  /// table, firmware/bench/measure_accuracy). Falls back to kResidual when no corner
  /// carries its noise (X-corners, chessboards).
  CovarianceModel covariance = CovarianceModel::kEdgeNoise;
  /// Error per corner coordinate (px) that neither the residuals nor the edge fits' noise
  /// can show, added to the covariance as independent: the part of the edge fit's bias
  /// that moves the pose along with the corners (the edge-fitted corners of clean renders
  /// are within 0.004-0.009 px of the truth, tests/camera_service/board_detector_test.cpp). 0 =
  /// none.
  double corner_floor_px = 0.0015;
  /// The floor grows by this gain times the square of the fitted erosion (px, at the image
  /// centre): the affine erosion field leaves a remainder (per tag, from the response curve
  /// and the defocus) that grows faster than the erosion and moves the pose with the
  /// corners. 0 = a fixed floor.
  double corner_floor_erosion_gain = 0.02;
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
  /// Fitted erosion of the dark features at the image centre (kPerTag: of the first tag), px (> 0:
  /// they look thinner than they are, as under a concave response), and its sigma; 0 when not
  /// fitted.
  double erosion_px = 0;
  double erosion_sigma_px = 0;
  int erosion_parameters = 0;  ///< nuisance parameters fitted (0, 1, 3 or one per tag)
  /// Per-axis standard deviation of each corner (input order), px: the per-corner noise the
  /// covariance is built from (CovarianceModel: the edge fits' noise, or the residuals' sigma,
  /// plus the excess and the floor), less the part of the excess a field smooth over the board
  /// explains (a wrong camera file's misfit, firmware/pose/corner_noise.h), plus the fitted
  /// erosion's share. Empty when not ok.
  std::vector<double> corner_sigma_px;
  /// Displacement of each corner (input order) that the fitted erosion explains, px:
  /// uv - corner_erosion_px[i] is the corner as the camera model sees it (the projection of
  /// the board point), the corner that pixel-space fits downstream must take (the corner
  /// path has no erosion term of its own). Zero when no erosion was fitted; empty when not ok.
  std::vector<Eigen::Vector2d> corner_erosion_px;
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

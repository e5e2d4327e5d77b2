// How well a camera's intrinsics are known and what their uncertainty does to board poses
// (common/README.md#the-camera-files-uncertainty).
//
// A calibration from views of a planar board estimates the intrinsics c (fx, fy, cx, cy,
// then the distortion coefficients in the file's order; CameraModel::IntrinsicJacobian)
// together with one pose per view. With each view's pixel residuals' Jacobians J_c (by c)
// and J_p (by the view's pose: body rotation, translation in C), the covariance of c alone
// is the inverse of the Schur complement over the poses,
//   C_c = s2 (sum_v J_c^T J_c - J_c^T J_p (J_p^T J_p)^-1 J_p^T J_c)^-1,
// s2 the residual variance per pixel axis (|r|^2 / (residuals - parameters)).
// A board pose solved from its corners with fixed pixels moves with the intrinsics by
//   dX_CT/dc = -(J_p^T J_p)^-1 J_p^T J_c,
// an error every pose measured with the same file shares: it does not average out over the
// poses as corner noise does (camera-model error is systematic, not random).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "common/camera/board_pose_fit.h"
#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"

namespace h4 {

/// One calibration view: its corners (weights 1/sigma, 0 left out) and the solved X_CT.
struct CalibrationViewFit {
  PoseCorners corners;
  RigidTransform X_CT;
};

struct IntrinsicsCovariance {
  Eigen::MatrixXd covariance;  ///< of fx, fy, cx, cy, distortion..., px^2 and 1
  double sigma_px = 0;         ///< the residuals' per-axis sigma that scales it
};

/// The intrinsics' covariance from the views that calibrated `camera` (formula above).
/// `tie_focal_lengths`: the calibration kept fx/fy at its ratio (one focal parameter; the
/// covariance of fx and fy is then fully correlated). `held`: intrinsics the calibration
/// held at their value (indices into fx, fy, cx, cy, distortion...; from 2 on), whose rows
/// and columns are then zero. nullopt when the views do not determine the intrinsics (a
/// singular Schur complement) or a corner is behind the camera.
std::optional<IntrinsicsCovariance> IntrinsicsCovarianceOf(
    const CameraIntrinsics& camera, const std::vector<CalibrationViewFit>& views,
    bool tie_focal_lengths, const std::vector<int>& held = {});

/// dX_CT/dc (6 x intrinsic count; body rotation, translation in C) of a board pose solved
/// from the points `p_TQ` seen at X_CT through `camera`, using those that project inside
/// the image. nullopt with fewer than 4 such points or a singular pose fit.
std::optional<Eigen::MatrixXd> BoardPoseByIntrinsics(const CameraIntrinsics& camera,
                                                     const std::vector<Eigen::Vector3d>& p_TQ,
                                                     const RigidTransform& X_CT);

}  // namespace h4

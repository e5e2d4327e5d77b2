// A board pose from its measured corners through a camera model: weighted Gauss-Newton on
// X_CT (a body rotation and a translation in C) from a start, the pose the corner path of
// the identification measures again once it has refined the intrinsics
// (host/identification/corner_identification.h), and the simulated camera's PnP.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"

namespace h4 {

/// The corners of one pose: board points and their measured pixels, with 1/sigma weights
/// (0: a rejected corner, left out).
struct PoseCorners {
  std::vector<Eigen::Vector3d> p_TQ;  ///< m, board frame
  std::vector<Eigen::Vector2d> uv;    ///< px, OpenCV convention
  std::vector<double> weight;         ///< 1 / sigma, 1/px
};

/// X_CT from `start`; false when fewer than 4 corners count, a corner falls behind the
/// camera, or the step is not finite. `covariance` (6x6: body rotation, translation in C;
/// (J^T J)^-1 of the weighted residuals) when non-null.
bool FitBoardPose(const PoseCorners& corners, const CameraIntrinsics& camera,
                  const RigidTransform& start, RigidTransform* X_CT,
                  Eigen::Matrix<double, 6, 6>* covariance = nullptr);

}  // namespace h4

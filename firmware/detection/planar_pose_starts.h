// Starts for fitting a planar board's pose X_CT through the lens model: IPPE
// (infinitesimal plane-based pose estimation, OpenCV's SOLVEPNP_IPPE) on the corners'
// undistorted normalised rays. IPPE knows no distortion, hence the rays; it returns the
// plane's two mirror-ambiguous solutions, which the caller refines and chooses between.
// Used by the pose estimator and by the tag prediction that finds missed tags.
#pragma once

#include <vector>

#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/detection/corner_observation.h"

namespace h4::cam {

/// IPPE's solutions X_CT from the corners (board point p_TQ, pixel uv). Corners whose ray
/// has no normalised coordinates (90 degrees or more off-axis) are left out. Empty with
/// fewer than 4 corners left or a degenerate (collinear) layout.
std::vector<RigidTransform> IppePlanarStarts(const std::vector<CornerObservation>& corners,
                                             const CameraModel& camera);

}  // namespace h4::cam

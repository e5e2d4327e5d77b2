// The camera block of the corner path's parameter vector
// (common/README.md#identification-from-corners): the intrinsics of the camera file as named
// parameters, camera.fx, camera.fy, camera.cx, camera.cy (px), then the distortion coefficients in
// the file's order (radtan camera.k1 camera.k2 camera.p1 camera.p2 [camera.k3 [k4 k5 k6]];
// equidistant camera.k1 .. camera.k4). The skew is held at the file's value.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"

namespace h4::host {

std::vector<std::string> CameraParameterNames(const CameraIntrinsics& camera);
Eigen::VectorXd CameraParameterValues(const CameraIntrinsics& camera);
/// `camera` with the block's values; precondition: values.size() == the names' count.
CameraIntrinsics WithCameraParameters(CameraIntrinsics camera, const Eigen::VectorXd& values);

/// Fixing preferences of the identifiability analysis for the camera block, after the
/// model's own (identifiability.h): the highest-order distortion first, focal lengths last.
std::vector<std::string> CameraFixPreferences(const CameraIntrinsics& camera);

}  // namespace h4::host

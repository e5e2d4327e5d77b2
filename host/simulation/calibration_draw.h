// A camera file as an ordinary intrinsic calibration leaves it: its covariance, and an
// error drawn from that covariance (the camera study and the corner-path tests: the truth is
// the renderer's camera, the file is what a calibration of it would say).
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"

namespace h4::host {

/// The covariance (common/camera/intrinsics_uncertainty.h) of a calibration of `camera`
/// from 25 views of a 9 x 6 chessboard of 25 mm squares, 0.3-0.5 m away, spread over the
/// image and tilted up to 35 deg, its corners with 0.1 px noise (a typical detector's).
/// Throws std::runtime_error when the views do not determine the intrinsics.
Eigen::MatrixXd ChessboardCalibrationCovariance(const CameraIntrinsics& camera);

/// `camera` with an error drawn from N(0, covariance) on fx, fy, cx, cy and the distortion
/// coefficients (first order: what a calibration with that covariance is off by).
CameraIntrinsics DrawnFromCovariance(CameraIntrinsics camera, const Eigen::MatrixXd& covariance,
                                     uint64_t seed);

}  // namespace h4::host

// Projection of points in the camera frame C to pixels through OpenCV's pinhole +
// distortion model (radial k1..k6 in rational form, tangential p1, p2), its analytic
// Jacobians, and the inverse (undistortion, by Gauss-Newton). Pixel convention:
// (0, 0) is the centre of the top-left pixel, as in OpenCV (formats.md).
#pragma once

#include <array>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"

namespace h4 {

class CameraModel {
 public:
  /// Takes 4, 5 or 8 distortion coefficients (OpenCV's order); any other count is
  /// treated as zero-padded to 8 after the first 8 (valid() tells whether the count was
  /// one of the supported ones).
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  /// False when the distortion vector has an unsupported length or fx, fy <= 0.
  bool valid() const { return valid_; }
  int width() const { return intrinsics_.width; }
  int height() const { return intrinsics_.height; }

  /// Distorted normalised coordinates of undistorted normalised ones (x/z, y/z),
  /// with the 2x2 Jacobian J_xd_xn when asked.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J_xd_xn = nullptr) const;

  /// Pixel of undistorted normalised coordinates, with J_uv_xn when asked.
  Eigen::Vector2d PixelFromNormalized(const Eigen::Vector2d& xn,
                                      Eigen::Matrix2d* J_uv_xn = nullptr) const;

  /// Pixel of a point p_CQ (m) in the camera frame, with the 2x3 Jacobian J_uv_pCQ.
  /// Returns false (uv untouched) when the point is not in front of the camera (z <= 0).
  bool Project(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv,
               Eigen::Matrix<double, 2, 3>* J_uv_pCQ = nullptr) const;

  /// Undistorted normalised coordinates of a pixel: the inverse of PixelFromNormalized,
  /// solved by Gauss-Newton to 1e-12 in normalised units. Returns false when it does not
  /// converge (far outside the calibrated field); *xn then holds the last iterate.
  bool NormalizedFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* xn) const;

  /// Pixel -> "ideal" pixel: K applied to the undistorted normalised coordinates, i.e.
  /// where the point would be imaged without distortion. Same convergence rule.
  bool IdealFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* ideal) const;

 private:
  CameraIntrinsics intrinsics_;
  std::array<double, 8> d_{};  // k1 k2 p1 p2 k3 k4 k5 k6
  double fx_ = 1, fy_ = 1, cx_ = 0, cy_ = 0, skew_ = 0;
  bool valid_ = false;
};

}  // namespace h4

// Undistorted ("ideal") coordinates of every pixel centre, solved once per camera so that
// edge fitting can work in a space where the board's straight edges are straight lines.
// Ideal coordinates: K applied to the undistorted normalised ray (camera_model.h), for
// either lens model (radtan or equidistant fisheye): straight lines in space are straight
// here. A pixel without a ray (a fisheye pixel 90 degrees or more off-axis, or beyond a
// lens fold; CameraModel::NormalizedFromPixel returns false) holds K applied to its
// distorted coordinates instead: finite, but not on any straight line.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_model.h"

namespace h4::cam {

class IdealPixelMap {
 public:
  explicit IdealPixelMap(const CameraModel& camera);

  int width() const { return width_; }
  int height() const { return height_; }
  /// Ideal coordinates of pixel centre (u, v); the caller keeps (u, v) inside the image.
  const Eigen::Vector2d& At(int u, int v) const {
    return ideal_[static_cast<size_t>(v) * static_cast<size_t>(width_) + static_cast<size_t>(u)];
  }
  /// Distorted pixel of an ideal point (the exact forward model).
  Eigen::Vector2d PixelFromIdeal(const Eigen::Vector2d& ideal) const;
  /// Ideal point of any pixel position (exact inverse, not interpolated).
  Eigen::Vector2d IdealFromPixel(const Eigen::Vector2d& uv) const;

 private:
  CameraModel camera_;
  int width_ = 0, height_ = 0;
  std::vector<Eigen::Vector2d> ideal_;
};

}  // namespace h4::cam

// Per-pixel undistortion table; see ideal_pixel_map.h.
#include "firmware/detection/ideal_pixel_map.h"

namespace h4::cam {

IdealPixelMap::IdealPixelMap(const CameraModel& camera)
    : camera_(camera), width_(std::max(camera.width(), 0)), height_(std::max(camera.height(), 0)) {
  ideal_.resize(static_cast<size_t>(width_) * static_cast<size_t>(height_));
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      camera_.IdealFromPixel(
          Eigen::Vector2d(u, v),
          &ideal_[static_cast<size_t>(v) * static_cast<size_t>(width_) + static_cast<size_t>(u)]);
    }
  }
}

Eigen::Vector2d IdealPixelMap::PixelFromIdeal(const Eigen::Vector2d& ideal) const {
  const Eigen::Matrix3d& K = camera_.intrinsics().K;
  const double yn = (ideal.y() - K(1, 2)) / K(1, 1);
  const double xn = (ideal.x() - K(0, 2) - K(0, 1) * yn) / K(0, 0);
  return camera_.PixelFromNormalized(Eigen::Vector2d(xn, yn));
}

Eigen::Vector2d IdealPixelMap::IdealFromPixel(const Eigen::Vector2d& uv) const {
  Eigen::Vector2d ideal;
  camera_.IdealFromPixel(uv, &ideal);
  return ideal;
}

}  // namespace h4::cam

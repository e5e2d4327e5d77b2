// Pinhole camera with OpenCV's distortion model (camera YAML, formats.md).
// Pixel convention: (0, 0) is the centre of the top-left pixel, as in OpenCV.
#pragma once

#include <optional>

#include <Eigen/Core>

namespace h4 {

struct CameraIntrinsics {
  int width = 0;   ///< image_width, px
  int height = 0;  ///< image_height, px
  /// camera_matrix [fx 0 cx; 0 fy cy; 0 0 1], px.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  /// distortion_coefficients in OpenCV's order (k1, k2, p1, p2[, k3[, k4, k5, k6]]):
  /// 4, 5 or 8 values.
  Eigen::VectorXd distortion = Eigen::VectorXd::Zero(5);
  std::optional<double> avg_reprojection_error;  ///< px, when the calibration wrote it
};

}  // namespace h4

// Camera intrinsics in OpenCV FileStorage YAML (formats.md "Camera intrinsics"), as
// OpenCV's calibration sample writes them: `%YAML:1.0` header, image_width,
// image_height, camera_matrix and distortion_coefficients as !!opencv-matrix (rows,
// cols, dt, data), optional avg_reprojection_error.
#pragma once

#include <string>

#include "common/camera/camera_intrinsics.h"

namespace h4 {

/// Reads the file (with or without the `%YAML:1.0` line and `---`; other top-level keys
/// such as calibration_time are ignored, keys inside a matrix must be rows/cols/dt/data).
/// Checks: positive image size; camera_matrix 3x3 with fx, fy > 0, K(1,0) = 0 and last
/// row (0, 0, 1); distortion_coefficients a 1xN or Nx1 matrix with N in {4, 5, 8};
/// dt 'd' or 'f'; rows * cols data values; avg_reprojection_error >= 0. Errors are
/// FormatErrors naming line and field ("camera_matrix.data[4]").
CameraIntrinsics ParseCameraYaml(const std::string& text, const std::string& source_name);
CameraIntrinsics ReadCameraYaml(const std::string& path);

/// Writes the layout OpenCV writes (readable by cv::FileStorage); every number has a
/// '.' or an exponent so that OpenCV reads it as a real, and reads back exactly.
std::string FormatCameraYaml(const CameraIntrinsics& camera);
void WriteCameraYaml(const std::string& path, const CameraIntrinsics& camera);

}  // namespace h4

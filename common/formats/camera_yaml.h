// Camera intrinsics files
// (common/formats/README.md#camera-intrinsics-opencv-filestorage-yaml-or-a-kalibr-camchain): OpenCV
// FileStorage YAML as OpenCV's calibration sample writes it (`%YAML:1.0` header, image_width,
// image_height, camera_matrix and distortion_coefficients as !!opencv-matrix (rows, cols, dt,
// data), optional avg_reprojection_error) with an optional distortion_model (radtan, the default,
// or equidistant); and, for reading, Kalibr's camchain.yaml (camera_model pinhole,
// distortion_model, intrinsics, distortion_coeffs, resolution).
#pragma once

#include <cstdint>
#include <string>

#include "common/camera/camera_intrinsics.h"
#include "common/formats/image_size.h"

namespace h4 {

/// Reads an OpenCV camera file (with or without the `%YAML:1.0` line and `---`; other
/// top-level keys such as calibration_time are ignored, keys inside a matrix must be
/// rows/cols/dt/data). Checks: image size kMinImageSide_px..kMaxImageSide_px a side and at
/// most kMaxImagePixels (image_size.h); camera_matrix 3x3 with fx, fy > 0,
/// K(1,0) = 0 and last row (0, 0, 1); distortion_model 'radtan' or 'equidistant' when
/// given; distortion_coefficients a 1xN or Nx1 matrix with N in {4, 5, 8} (radtan) or
/// N = 4 (equidistant); dt 'd' or 'f'; rows * cols data values; avg_reprojection_error
/// >= 0.
/// A file with a `camera_model` key (one Kalibr camera block) or `cam0`/`cam1` keys (a
/// camchain) is read as Kalibr's: camera_model 'pinhole', distortion_model 'radtan' or
/// 'equidistant', intrinsics [fu, fv, pu, pv] (fu, fv > 0), distortion_coeffs 4 numbers,
/// resolution [w, h] (the same size limits); other keys (T_cam_imu, rostopic, ...) are ignored. A
/// camchain with several cameras needs `kalibr_camera` ("cam1"); one with a single camera uses it.
/// Errors are FormatErrors naming line and field ("camera_matrix.data[4]",
/// "cam0.distortion_coeffs").
CameraIntrinsics ParseCameraYaml(const std::string& text, const std::string& source_name,
                                 const std::string& kalibr_camera = "");
/// Empty when `camera` holds what the camera file's reader accepts (the bounds physics
/// allows): an image size within image_size.h's limits, finite positive focal lengths, a
/// finite skew, the principal point within the image, a supported number of finite
/// distortion coefficients, a lens model one to one over the image
/// (CameraModel::FoldInsideImage); else why. For the intrinsics other files carry (the
/// identification result's `camera` key).
std::string CameraIntrinsicsProblem(const CameraIntrinsics& camera);

/// Reads `path`; "camchain.yaml#cam1" reads camera cam1 of a Kalibr camchain.
CameraIntrinsics ReadCameraYaml(const std::string& path);

/// Writes the layout OpenCV writes (readable by cv::FileStorage) plus distortion_model;
/// every number has a '.' or an exponent so that OpenCV reads it as a real, and reads
/// back exactly.
std::string FormatCameraYaml(const CameraIntrinsics& camera);
void WriteCameraYaml(const std::string& path, const CameraIntrinsics& camera);

}  // namespace h4

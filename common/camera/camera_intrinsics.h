// Pinhole camera intrinsics with one of two distortion models (camera YAML,
// common/formats/README.md#camera-intrinsics-opencv-filestorage-yaml-or-a-kalibr-camchain):
// OpenCV's radial-tangential model, or the equidistant fisheye model of OpenCV's cv::fisheye
// (Kalibr's pinhole-equi). Pixel convention: (0, 0) is the centre of the top-left pixel, as in
// OpenCV.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

namespace h4 {

enum class DistortionModel {
  /// OpenCV's pinhole distortion (cv::projectPoints; Kalibr "radtan"): coefficients
  /// k1 k2 p1 p2 [k3 [k4 k5 k6]], 4, 5 or 8 of them (8: the rational model); none = no
  /// distortion.
  kRadTan,
  /// Equidistant fisheye (cv::fisheye; Kalibr "equidistant"): a ray at angle theta from
  /// the optical axis is imaged at normalised radius
  /// theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8);
  /// coefficients k1 k2 k3 k4 (none = the plain f-theta lens).
  kEquidistant,
};

/// "radtan" or "equidistant", the names of the camera YAML and of Kalibr.
const char* ToString(DistortionModel model);
/// The model named `name` ("radtan", "equidistant"), nullopt for any other name.
std::optional<DistortionModel> DistortionModelFromName(const std::string& name);
/// Whether `count` coefficients suit `model` (radtan: 0, 4, 5, 8; equidistant: 0, 4).
bool IsSupportedDistortionCount(DistortionModel model, Eigen::Index count);
/// The coefficient counts a file must give for `model`, for error messages
/// ("4, 5 or 8 (k1 k2 p1 p2 [k3 [k4 k5 k6]])").
std::string ExpectedDistortionCoefficients(DistortionModel model);

struct CameraIntrinsics {
  int width = 0;   ///< image_width, px
  int height = 0;  ///< image_height, px
  /// camera_matrix [fx s cx; 0 fy cy; 0 0 1], px.
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  /// Which model `distortion` is for; radtan unless a file says otherwise.
  DistortionModel distortion_model = DistortionModel::kRadTan;
  /// distortion_coefficients in OpenCV's order for distortion_model (see DistortionModel).
  Eigen::VectorXd distortion = Eigen::VectorXd::Zero(5);
  std::optional<double> avg_reprojection_error;  ///< px, when the calibration wrote it
  /// The calibration's covariance of fx, fy, cx, cy, then the distortion coefficients in
  /// their order (CameraModel::IntrinsicJacobian's order; px^2, px, 1), when it wrote one
  /// (camera YAML `intrinsics_covariance`, common/camera/intrinsics_uncertainty.h).
  std::optional<Eigen::MatrixXd> intrinsics_covariance;

  /// A width x height px camera with focal lengths (fx, fy) and principal point (cx, cy),
  /// px, no skew, and no distortion until the caller sets one.
  static CameraIntrinsics Pinhole(int width, int height, double fx, double fy, double cx,
                                  double cy);
};

}  // namespace h4

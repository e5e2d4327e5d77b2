// Projection of points in the camera frame C to pixels through a pinhole camera with
// OpenCV's radial-tangential distortion (k1..k6 in rational form, p1, p2) or the
// equidistant fisheye distortion of cv::fisheye (camera_intrinsics.h), their analytic
// Jacobians, and the inverse (undistortion). Pixel convention: (0, 0) is the centre of
// the top-left pixel, as in OpenCV (common/formats/README.md).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"

namespace h4 {

class CameraModel {
 public:
  /// Takes the coefficients of intrinsics.distortion_model (IsSupportedDistortionCount);
  /// any other count is treated as zero-padded after the first 8 (valid() tells whether
  /// the count was a supported one).
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }
  DistortionModel distortion_model() const { return intrinsics_.distortion_model; }
  /// False when the distortion vector has an unsupported length for the model or fx, fy <= 0.
  bool valid() const { return valid_; }
  int width() const { return intrinsics_.width; }
  int height() const { return intrinsics_.height; }

  /// The largest angle from the optical axis (rad) the model images one to one: pi/2, or
  /// less where the radial map stops increasing (a lens polynomial that folds back: past
  /// the fold two rays share a pixel and the image shrinks back toward the centre).
  /// Equidistant: where d theta_d / d theta reaches 0. Radtan: where d r_d / d r of the
  /// radial part r_d = r g(r^2) reaches 0 (or its rational denominator does). Computed once.
  double max_field_angle() const { return max_theta_; }

  /// Whether the point p_CQ (camera frame) is in front of the camera and inside the field
  /// the model images one to one (max_field_angle()). A projection decides visibility
  /// only there: beyond the fold the formulas return pixels inside the image for points
  /// the lens never shows there.
  bool InValidField(const Eigen::Vector3d& p_CQ) const;

  /// Project(), refused (false, uv untouched) outside InValidField(): what deciding
  /// whether a point is seen, and where, must use.
  bool ProjectVisible(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv) const;

  /// The largest angle from the optical axis (rad) whose rays the lens images one to one,
  /// beyond 90 degrees where the model allows it: equidistant, the first fold of
  /// theta_d(theta) in (0, pi] (a 190-degree fisheye sees rays 95 degrees off-axis, behind
  /// the camera's image plane); radtan, max_field_angle() (a pinhole has no ray at 90
  /// degrees or more).
  double max_ray_angle() const { return max_ray_theta_; }

  /// Where the lens model folds inside the image, if it does: the image's farthest pixel
  /// (a corner of the image) lies beyond the distorted radius the radial map reaches at its
  /// first fold (max_ray_angle()), so that part of the image has no ray, or two (a fit on
  /// corners that cover little of the image can give such a model: issue 42 point 19). The
  /// tangential terms are left out, as in max_field_angle(). Empty when the model is one to
  /// one over the whole image, else why ("the lens model folds about 291 px from the
  /// principal point (39.1 deg off the axis) but the image reaches 640 px: ...").
  std::string FoldInsideImage() const;

  /// Pixel of a point p_CQ (m) seen at any angle up to max_ray_angle() from the axis, z <= 0
  /// included on a fisheye; false (uv untouched) beyond it or at the camera centre.
  bool ProjectRay(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv) const;

  /// Unit direction (camera frame) of the ray imaged at pixel uv, up to max_ray_angle();
  /// false (ray untouched) beyond it, or where NormalizedFromPixel fails on radtan.
  bool RayFromPixel(const Eigen::Vector2d& uv, Eigen::Vector3d* ray_C) const;

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

  /// The intrinsics a calibration refines, in this order: fx, fy, cx, cy, then the
  /// distortion coefficients in the file's order (the skew is held).
  int intrinsic_count() const { return 4 + static_cast<int>(intrinsics_.distortion.size()); }
  /// d uv / d(fx, fy, cx, cy, distortion...) at a point in front of the camera
  /// (2 x intrinsic_count()); false (J untouched) when z <= 0.
  bool IntrinsicJacobian(const Eigen::Vector3d& p_CQ, Eigen::MatrixXd* J_uv_intrinsics) const;

  /// Undistorted normalised coordinates of a pixel: the inverse of PixelFromNormalized to
  /// 1e-10 in distorted normalised units. Radtan: Gauss-Newton from the distorted point;
  /// returns false when it does not converge (far outside the calibrated field), *xn then
  /// holds the last iterate. Equidistant: the angle theta solved in one dimension
  /// (bracketed Newton), exact up to max_field_angle(); returns false for pixels at or
  /// beyond that angle (rays at 90 degrees or more from the axis have no normalised
  /// coordinates; beyond a fold the pixel has two rays), *xn then holds the finite
  /// distorted normalised coordinates.
  bool NormalizedFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* xn) const;

  /// Pixel -> "ideal" pixel: K applied to the undistorted normalised coordinates, i.e.
  /// where the point would be imaged without distortion. Same convergence rule.
  bool IdealFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* ideal) const;

 private:
  Eigen::Vector2d DistortRadTan(const Eigen::Vector2d& xn, Eigen::Matrix2d* J_xd_xn) const;
  Eigen::Vector2d DistortEquidistant(const Eigen::Vector2d& xn, Eigen::Matrix2d* J_xd_xn) const;
  bool UndistortRadTan(const Eigen::Vector2d& xd, Eigen::Vector2d* xn) const;
  bool UndistortEquidistant(const Eigen::Vector2d& xd, Eigen::Vector2d* xn) const;
  /// theta_d(theta) of the equidistant model, and its derivative when asked.
  double EquidistantThetaD(double theta, double* dthetad_dtheta = nullptr) const;
  /// d r_d / d r of the radial-tangential model's radial part at normalised radius r
  /// (non-positive also where the rational denominator is).
  double RadTanRadialSlope(double r) const;
  /// The first angle in (0, limit] where slope(theta) stops being positive; limit if never.
  template <class Slope>
  static double FirstFold(const Slope& slope, double limit);
  /// Equidistant: theta with theta_d(theta) = theta_d on [0, max_theta], false past it.
  bool EquidistantTheta(double theta_d, double max_theta, double* theta) const;

  CameraIntrinsics intrinsics_;
  std::array<double, 8> d_{};  // radtan: k1 k2 p1 p2 k3 k4 k5 k6; equidistant: k1 k2 k3 k4
  double fx_ = 1, fy_ = 1, cx_ = 0, cy_ = 0, skew_ = 0;
  double max_theta_ = 0;        // see max_field_angle()
  double max_theta_d_ = 0;      // equidistant: EquidistantThetaD(max_theta_)
  double max_r_ = 0;            // tan(max_theta_), or infinity at pi/2
  double max_ray_theta_ = 0;    // see max_ray_angle()
  double max_ray_theta_d_ = 0;  // equidistant: EquidistantThetaD(max_ray_theta_)
  bool valid_ = false;
};

}  // namespace h4

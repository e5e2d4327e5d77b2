// Camera intrinsics from several views of a planar board (Zhang's method): pinhole +
// OpenCV's 5-coefficient or rational 8-coefficient distortion (cv::calibrateCamera), or
// the equidistant fisheye model (cv::fisheye::calibrate); per-view RMS reprojection
// errors, outlier views named (and optionally dropped, then recalibrated) by a stated
// rule, and view sets that cannot determine the focal length refused with the reason.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/camera/camera_intrinsics.h"
#include "firmware/calibration/board_views.h"

namespace h4::cam {

/// The lens model to calibrate (camera_intrinsics.h).
/// Named by ToString, in this order (intrinsics_calibration.cpp).
enum class IntrinsicsModel {
  kRadTan,       ///< radtan, k1 k2 p1 p2 k3 (cv::calibrateCamera)
  kRational,     ///< radtan, k1 k2 p1 p2 k3 k4 k5 k6 (cv::CALIB_RATIONAL_MODEL)
  kEquidistant,  ///< equidistant fisheye, k1 k2 k3 k4 (cv::fisheye::calibrate)
};
/// "radtan", "rational", "equidistant".
const char* ToString(IntrinsicsModel model);

struct IntrinsicsCalibrationOptions {
  IntrinsicsModel model = IntrinsicsModel::kRadTan;
  int min_views = 8;              ///< fewer views with the board: no calibration
  bool fix_aspect_ratio = false;  ///< fx = fy (CALIB_FIX_ASPECT_RATIO with ratio 1); not
                                  ///< with kEquidistant (cv::fisheye has no such flag)
  /// Observability of the focal length (Zhang's method needs the board seen tilted, in
  /// several orientations): two views are distinct when their board normals differ by at
  /// least min_orientation_difference_deg; fewer than min_distinct_orientations distinct
  /// views, or no view tilted at least min_tilt_deg from fronto-parallel, and the
  /// calibration is refused (kDegenerateViews). Normals from the calibrated poses.
  double min_orientation_difference_deg = 5.0;
  int min_distinct_orientations = 3;
  double min_tilt_deg = 10.0;
  /// Outlier rule: a view whose RMS error exceeds outlier_factor x the median per-view RMS
  /// is an outlier (a blurred image, a mis-detected corner); 3 flags OpenCV's left02.jpg.
  double outlier_factor = 3.0;
  /// Drop the outlier views and calibrate once more on the others (if >= min_views remain).
  bool drop_outliers = false;
  /// Hold k3 at 0 (not with kEquidistant). CalibrateIntrinsics does so by itself when a
  /// radtan fit with k3 free folds inside the image.
  bool hold_k3 = false;

  bool IsValid(std::string* why) const;
};

struct ViewReport {
  std::string name;
  int points = 0;
  double rms_px = 0;     ///< RMS reprojection error of this view, px
  double tilt_deg = 0;   ///< angle between the board normal and the optical axis, deg
  bool outlier = false;  ///< by the rule of IntrinsicsCalibrationOptions::outlier_factor
  bool used = true;      ///< in the final calibration (false once dropped)
  /// The corners found, px, and their residuals (found - reprojected), px, in the
  /// calibration that last used the view (the first one for a dropped view).
  std::vector<cv::Point2f> corners_px;
  std::vector<cv::Point2f> residuals_px;
};

struct IntrinsicsCalibrationResult {
  /// kFoldingDistortion: the fitted lens model folds inside the image
  /// (CameraModel::FoldInsideImage), so part of the image would have no ray.
  enum class Status {
    kOk,
    kInvalidOptions,
    kTooFewViews,
    kDegenerateViews,
    kFoldingDistortion,
    kFailed
  };
  Status status = Status::kFailed;
  std::string message;      ///< why it is not kOk, or a note (outliers dropped)
  CameraIntrinsics camera;  ///< with avg_reprojection_error = rms_px
  IntrinsicsModel model = IntrinsicsModel::kRadTan;
  double rms_px = 0;  ///< RMS reprojection error over every used point, px
  double median_view_rms_px = 0;
  double outlier_limit_px = 0;  ///< outlier_factor x median_view_rms_px
  std::vector<ViewReport> views;
  int views_used = 0;
  int distinct_orientations = 0;  ///< among the used views (see the options)
  double max_tilt_deg = 0;        ///< largest board tilt from fronto-parallel, deg
  /// The per-axis residual sigma s that scales camera.intrinsics_covariance (the fit's
  /// Jacobian with the board poses marginalised, times s^2 = |r|^2 / (residuals -
  /// parameters); intrinsics_uncertainty.h), px; 0 when there is no covariance.
  double residual_sigma_px = 0;

  bool ok() const { return status == Status::kOk; }
  /// Multi-line report: the parameters with their 1-sigma, RMS, one line per view with
  /// outliers marked.
  std::string Report() const;
};

/// Calibrates from `views` (every image of `image_size`). Never throws; never returns NaN
/// in an ok() result (a non-finite solution is kFailed).
IntrinsicsCalibrationResult CalibrateIntrinsics(const std::vector<CalibrationView>& views,
                                                cv::Size image_size,
                                                const IntrinsicsCalibrationOptions& options);

}  // namespace h4::cam

// Camera intrinsics from several views of a planar board (Zhang's method through
// cv::calibrateCamera): pinhole + OpenCV's 5-coefficient distortion, per-view RMS
// reprojection errors, and outlier views named (and optionally dropped, then
// recalibrated) by a stated rule.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/camera/camera_intrinsics.h"
#include "firmware/calibration/board_views.h"

namespace h4::cam {

struct IntrinsicsCalibrationOptions {
  int min_views = 8;              ///< fewer views with the board: no calibration
  bool fix_aspect_ratio = false;  ///< fx = fy (CALIB_FIX_ASPECT_RATIO with ratio 1)
  /// Outlier rule: a view whose RMS error exceeds outlier_factor x the median per-view RMS
  /// is an outlier (a blurred image, a mis-detected corner); 3 flags OpenCV's left02.jpg.
  double outlier_factor = 3.0;
  /// Drop the outlier views and calibrate once more on the others (if >= min_views remain).
  bool drop_outliers = false;

  bool IsValid(std::string* why) const;
};

struct ViewReport {
  std::string name;
  int points = 0;
  double rms_px = 0;     ///< RMS reprojection error of this view, px
  bool outlier = false;  ///< by the rule of IntrinsicsCalibrationOptions::outlier_factor
  bool used = true;      ///< in the final calibration (false once dropped)
};

struct IntrinsicsCalibrationResult {
  enum class Status { kOk, kInvalidOptions, kTooFewViews, kFailed };
  Status status = Status::kFailed;
  std::string message;      ///< why it is not kOk, or a note (outliers dropped)
  CameraIntrinsics camera;  ///< with avg_reprojection_error = rms_px
  double rms_px = 0;        ///< RMS reprojection error over every used point, px
  double median_view_rms_px = 0;
  double outlier_limit_px = 0;  ///< outlier_factor x median_view_rms_px
  std::vector<ViewReport> views;
  int views_used = 0;

  bool ok() const { return status == Status::kOk; }
  /// Multi-line report: K, distortion, RMS, one line per view with outliers marked.
  std::string Report() const;
};

/// Calibrates from `views` (every image of `image_size`). Never throws; never returns NaN
/// in an ok() result (a non-finite solution is kFailed).
IntrinsicsCalibrationResult CalibrateIntrinsics(const std::vector<CalibrationView>& views,
                                                cv::Size image_size,
                                                const IntrinsicsCalibrationOptions& options);

}  // namespace h4::cam

// Intrinsics calibration; see intrinsics_calibration.h.
#include "firmware/calibration/intrinsics_calibration.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>

namespace h4::cam {
namespace {

struct Solution {
  cv::Mat K, distortion;
  double rms_px = 0;
  std::vector<double> view_rms_px;
};

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + static_cast<long>(mid)));
}

bool Solve(const std::vector<const CalibrationView*>& views, cv::Size image_size,
           bool fix_aspect_ratio, Solution* solution, std::string* error) {
  std::vector<std::vector<cv::Point3f>> object_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  for (const auto* view : views) {
    object_points.push_back(view->object_points);
    image_points.push_back(view->image_points);
  }
  // With CALIB_FIX_ASPECT_RATIO OpenCV keeps the ratio fx/fy of the input matrix (1 here).
  cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  cv::Mat distortion = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const int flags = fix_aspect_ratio ? cv::CALIB_FIX_ASPECT_RATIO : 0;
  try {
    solution->rms_px = cv::calibrateCamera(object_points, image_points, image_size, K, distortion,
                                           rvecs, tvecs, flags);
  } catch (const cv::Exception& e) {
    *error = std::string("cv::calibrateCamera failed: ") + e.what();
    return false;
  }
  solution->view_rms_px.clear();
  for (size_t i = 0; i < views.size(); ++i) {
    std::vector<cv::Point2f> projected;
    cv::projectPoints(object_points[i], rvecs[i], tvecs[i], K, distortion, projected);
    const double sum_sq = std::pow(cv::norm(image_points[i], projected, cv::NORM_L2), 2);
    solution->view_rms_px.push_back(std::sqrt(sum_sq / static_cast<double>(projected.size())));
  }
  solution->K = K;
  solution->distortion = distortion;
  if (!cv::checkRange(K) || !cv::checkRange(distortion) || !std::isfinite(solution->rms_px)) {
    *error = "cv::calibrateCamera returned a non-finite solution";
    return false;
  }
  return true;
}

std::string Fixed(double value) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << value;
  return out.str();
}

}  // namespace

bool IntrinsicsCalibrationOptions::IsValid(std::string* why) const {
  if (min_views < 3) {
    *why = "min_views must be >= 3 (Zhang's method needs 3 views of a plane), got " +
           std::to_string(min_views);
    return false;
  }
  if (!(outlier_factor > 1.0)) {
    *why = "outlier_factor must be > 1, got " + std::to_string(outlier_factor);
    return false;
  }
  return true;
}

IntrinsicsCalibrationResult CalibrateIntrinsics(const std::vector<CalibrationView>& views,
                                                cv::Size image_size,
                                                const IntrinsicsCalibrationOptions& options) {
  IntrinsicsCalibrationResult result;
  if (!options.IsValid(&result.message)) {
    result.status = IntrinsicsCalibrationResult::Status::kInvalidOptions;
    return result;
  }
  for (const auto& view : views) {
    result.views.push_back({view.name, static_cast<int>(view.image_points.size()), 0, false, true});
  }
  if (static_cast<int>(views.size()) < options.min_views) {
    result.status = IntrinsicsCalibrationResult::Status::kTooFewViews;
    result.message = std::to_string(views.size()) + " view(s) with the board, expected at least " +
                     std::to_string(options.min_views);
    return result;
  }

  std::vector<const CalibrationView*> used;
  for (const auto& view : views) used.push_back(&view);
  Solution solution;
  if (!Solve(used, image_size, options.fix_aspect_ratio, &solution, &result.message)) return result;
  result.median_view_rms_px = Median(solution.view_rms_px);
  const double limit = options.outlier_factor * result.median_view_rms_px;
  result.outlier_limit_px = limit;
  std::vector<std::string> outliers;
  for (size_t i = 0; i < views.size(); ++i) {
    result.views[i].rms_px = solution.view_rms_px[i];
    result.views[i].outlier = solution.view_rms_px[i] > limit;
    if (result.views[i].outlier) outliers.push_back(views[i].name);
  }

  if (options.drop_outliers && !outliers.empty()) {
    std::vector<const CalibrationView*> kept;
    for (size_t i = 0; i < views.size(); ++i) {
      if (!result.views[i].outlier) kept.push_back(&views[i]);
    }
    if (static_cast<int>(kept.size()) < options.min_views) {
      result.message = "outliers kept: dropping them would leave " + std::to_string(kept.size()) +
                       " view(s), fewer than " + std::to_string(options.min_views);
    } else {
      Solution again;
      if (!Solve(kept, image_size, options.fix_aspect_ratio, &again, &result.message)) {
        return result;
      }
      solution = again;
      size_t k = 0;
      for (auto& view : result.views) {
        view.used = !view.outlier;
        view.rms_px = view.used ? solution.view_rms_px[k++] : view.rms_px;
      }
      result.message =
          "dropped " + std::to_string(outliers.size()) + " outlier view(s) and recalibrated";
    }
  }

  result.rms_px = solution.rms_px;
  result.views_used = static_cast<int>(std::count_if(result.views.begin(), result.views.end(),
                                                     [](const auto& v) { return v.used; }));
  result.camera.width = image_size.width;
  result.camera.height = image_size.height;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) result.camera.K(r, c) = solution.K.at<double>(r, c);
  }
  result.camera.distortion.resize(static_cast<Eigen::Index>(solution.distortion.total()));
  for (int i = 0; i < static_cast<int>(solution.distortion.total()); ++i) {
    result.camera.distortion(i) = solution.distortion.at<double>(i);
  }
  result.camera.avg_reprojection_error = result.rms_px;
  result.status = IntrinsicsCalibrationResult::Status::kOk;
  return result;
}

std::string IntrinsicsCalibrationResult::Report() const {
  std::ostringstream out;
  if (!ok()) {
    out << "calibration failed: " << message << "\n";
    return out.str();
  }
  const auto& K = camera.K;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << "image " << camera.width << "x" << camera.height << ", " << views_used << " of "
      << views.size() << " views used\n"
      << "fx " << K(0, 0) << "  fy " << K(1, 1) << "  cx " << K(0, 2) << "  cy " << K(1, 2)
      << " px\n"
      << "distortion (k1 k2 p1 p2 k3):";
  out.precision(5);
  for (Eigen::Index i = 0; i < camera.distortion.size(); ++i) out << " " << camera.distortion(i);
  out.precision(4);
  out << "\nRMS reprojection error " << rms_px << " px (median per view " << median_view_rms_px
      << " px)\n";
  for (const auto& view : views) {
    out << "  " << view.name << ": " << view.points << " points, RMS " << view.rms_px << " px"
        << (view.outlier ? "  OUTLIER (first RMS > " + Fixed(outlier_limit_px) + " px)" : "")
        << (view.used ? "" : ", dropped") << "\n";
  }
  if (!message.empty()) out << message << "\n";
  return out.str();
}

}  // namespace h4::cam

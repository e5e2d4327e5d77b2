// Intrinsics calibration; see intrinsics_calibration.h.
#include "firmware/calibration/intrinsics_calibration.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <iterator>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>

#include "common/camera/camera_model.h"
#include "common/camera/intrinsics_uncertainty.h"
#include "common/text/enum_names.h"
#include "common/units.h"
#include "firmware/calibration/intrinsics_report.h"

namespace h4::cam {
namespace {

struct Solution {
  cv::Mat K, distortion;
  double rms_px = 0;
  std::vector<double> view_rms_px;
  std::vector<std::vector<cv::Point2f>> residuals_px;  ///< per view: found - reprojected
  std::vector<cv::Vec3d> board_normals;                ///< per view, in the camera frame
  std::vector<CalibrationViewFit> fits;                ///< per view, its corners and X_CT
};

double Median(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + static_cast<long>(mid)));
}

// OpenCV's two calibration back ends; both fill K, distortion, rvecs and tvecs and
// return the RMS reprojection error.
double CalibratePinhole(const std::vector<std::vector<cv::Point3f>>& object_points,
                        const std::vector<std::vector<cv::Point2f>>& image_points,
                        cv::Size image_size, const IntrinsicsCalibrationOptions& options,
                        cv::Mat* K, cv::Mat* distortion, std::vector<cv::Mat>* rvecs,
                        std::vector<cv::Mat>* tvecs) {
  // With CALIB_FIX_ASPECT_RATIO OpenCV keeps the ratio fx/fy of the input matrix (1 here).
  *K = cv::Mat::eye(3, 3, CV_64F);
  const bool rational = options.model == IntrinsicsModel::kRational;
  *distortion = cv::Mat::zeros(rational ? 8 : 5, 1, CV_64F);
  int flags = options.fix_aspect_ratio ? cv::CALIB_FIX_ASPECT_RATIO : 0;
  if (rational) flags |= cv::CALIB_RATIONAL_MODEL;
  if (options.hold_k3) flags |= cv::CALIB_FIX_K3;
  // OpenCV's default stops after 30 iterations; the rational model's 8 coefficients,
  // strongly correlated, are still moving then (0.03 px at the corner on exact data).
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                  rational ? 200 : 30, DBL_EPSILON);
  return cv::calibrateCamera(object_points, image_points, image_size, *K, *distortion, *rvecs,
                             *tvecs, flags, criteria);
}

double CalibrateFisheye(const std::vector<std::vector<cv::Point3f>>& object_points,
                        const std::vector<std::vector<cv::Point2f>>& image_points,
                        cv::Size image_size, cv::Mat* K, cv::Mat* distortion,
                        std::vector<cv::Mat>* rvecs, std::vector<cv::Mat>* tvecs) {
  *K = cv::Mat::eye(3, 3, CV_64F);
  *distortion = cv::Mat::zeros(4, 1, CV_64F);
  // Zero skew, as the pinhole back end; extrinsics re-estimated at every iteration (what
  // OpenCV's fisheye sample does: the initial per-view poses are poor on wide lenses).
  const int flags = cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW;
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12);
  return cv::fisheye::calibrate(object_points, image_points, image_size, *K, *distortion, *rvecs,
                                *tvecs, flags, criteria);
}

void ProjectView(const std::vector<cv::Point3f>& object_points, const cv::Mat& rvec,
                 const cv::Mat& tvec, const cv::Mat& K, const cv::Mat& distortion,
                 IntrinsicsModel model, std::vector<cv::Point2f>* projected) {
  if (model == IntrinsicsModel::kEquidistant) {
    cv::fisheye::projectPoints(object_points, *projected, rvec, tvec, K, distortion);
  } else {
    cv::projectPoints(object_points, rvec, tvec, K, distortion, *projected);
  }
}

// A view's corners (unit weights) and the pose the calibration solved for it.
CalibrationViewFit ViewFit(const std::vector<cv::Point3f>& object_points,
                           const std::vector<cv::Point2f>& image_points, const cv::Mat& rvec,
                           const cv::Mat& tvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d R_CT;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_CT(r, c) = R(r, c);
  }
  const cv::Vec3d t = tvec;
  CalibrationViewFit fit{{}, RigidTransform(R_CT, Eigen::Vector3d(t[0], t[1], t[2]))};
  for (size_t k = 0; k < object_points.size(); ++k) {
    fit.corners.p_TQ.emplace_back(object_points[k].x, object_points[k].y, object_points[k].z);
    fit.corners.uv.emplace_back(image_points[k].x, image_points[k].y);
    fit.corners.weight.push_back(1.0);
  }
  return fit;
}

bool Solve(const std::vector<const CalibrationView*>& views, cv::Size image_size,
           const IntrinsicsCalibrationOptions& options, Solution* solution, std::string* error) {
  std::vector<std::vector<cv::Point3f>> object_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  for (const auto* view : views) {
    object_points.push_back(view->object_points);
    image_points.push_back(view->image_points);
  }
  cv::Mat K, distortion;
  std::vector<cv::Mat> rvecs, tvecs;
  const bool fisheye = options.model == IntrinsicsModel::kEquidistant;
  try {
    solution->rms_px = fisheye ? CalibrateFisheye(object_points, image_points, image_size, &K,
                                                  &distortion, &rvecs, &tvecs)
                               : CalibratePinhole(object_points, image_points, image_size, options,
                                                  &K, &distortion, &rvecs, &tvecs);
  } catch (const cv::Exception& e) {
    *error = std::string(fisheye ? "cv::fisheye::calibrate" : "cv::calibrateCamera") +
             " failed: " + e.what();
    return false;
  }
  if (!cv::checkRange(K) || !cv::checkRange(distortion) || !std::isfinite(solution->rms_px)) {
    *error = "the calibration returned a non-finite solution";
    return false;
  }
  solution->view_rms_px.clear();
  solution->residuals_px.clear();
  solution->board_normals.clear();
  solution->fits.clear();
  for (size_t i = 0; i < views.size(); ++i) {
    solution->fits.push_back(ViewFit(object_points[i], image_points[i], rvecs[i], tvecs[i]));
    std::vector<cv::Point2f> projected;
    ProjectView(object_points[i], rvecs[i], tvecs[i], K, distortion, options.model, &projected);
    const double sum_sq = std::pow(cv::norm(image_points[i], projected, cv::NORM_L2), 2);
    solution->view_rms_px.push_back(std::sqrt(sum_sq / static_cast<double>(projected.size())));
    std::vector<cv::Point2f> residuals(projected.size());
    for (size_t k = 0; k < projected.size(); ++k) residuals[k] = image_points[i][k] - projected[k];
    solution->residuals_px.push_back(std::move(residuals));
    cv::Matx33d R_CT;
    cv::Rodrigues(rvecs[i], R_CT);
    solution->board_normals.emplace_back(R_CT(0, 2), R_CT(1, 2), R_CT(2, 2));
  }
  solution->K = K;
  solution->distortion = distortion;
  return true;
}

double AngleDeg(const cv::Vec3d& a, const cv::Vec3d& b) {
  return DegreesFromRadians(
      std::acos(std::clamp(a.dot(b) / (cv::norm(a) * cv::norm(b)), -1.0, 1.0)));
}

double TiltDeg(const cv::Vec3d& board_normal) {
  return DegreesFromRadians(
      std::acos(std::min(1.0, std::abs(board_normal[2]) / cv::norm(board_normal))));
}

// Greedy clustering of the board normals: a view starts a new orientation when it is at
// least `min_difference_deg` from every orientation found so far.
int DistinctOrientations(const std::vector<cv::Vec3d>& normals, double min_difference_deg) {
  std::vector<cv::Vec3d> distinct;
  for (const cv::Vec3d& n : normals) {
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const cv::Vec3d& d) {
      return AngleDeg(n, d) < min_difference_deg;
    });
    if (!seen) distinct.push_back(n);
  }
  return static_cast<int>(distinct.size());
}

// Zhang's method determines the focal length only from views of the board tilted in
// different directions: with one orientation (or copies of one image) or only
// fronto-parallel views, any focal length fits (8 copies of one image gave fx 8379 for
// a true 817 at 0.02 px RMS). The reason, or "" when the views are fine.
std::string FocalLengthObservability(const Solution& solution,
                                     const IntrinsicsCalibrationOptions& options,
                                     IntrinsicsCalibrationResult* result) {
  result->distinct_orientations =
      DistinctOrientations(solution.board_normals, options.min_orientation_difference_deg);
  result->max_tilt_deg = 0;
  for (const cv::Vec3d& n : solution.board_normals) {
    result->max_tilt_deg = std::max(result->max_tilt_deg, TiltDeg(n));
  }
  if (result->distinct_orientations < options.min_distinct_orientations) {
    return fmt::format(
        "focal length not observable: the views show the board in {} distinct orientation(s) "
        "(normals at least {:.3g} deg apart), expected at least {}; duplicate images or one pose "
        "repeated cannot calibrate: tilt the board in different directions",
        result->distinct_orientations, options.min_orientation_difference_deg,
        options.min_distinct_orientations);
  }
  if (result->max_tilt_deg < options.min_tilt_deg) {
    return fmt::format(
        "focal length not observable: every view is nearly fronto-parallel (largest tilt {:.3g} "
        "deg, expected at least {:.3g} deg): tilt the board towards and away from the camera",
        result->max_tilt_deg, options.min_tilt_deg);
  }
  return "";
}

/// "k1 k2 p1 p2 k3": the distortion coefficients' names, in the file's order.
std::string DistortionNames(const IntrinsicsCalibrationResult& result) {
  std::string names;
  const std::vector<ParameterRow> rows = ParameterRows(result);
  for (size_t i = 4; i < rows.size(); ++i) names += (i > 4 ? " " : "") + rows[i].name;
  return names;
}

/// The parameters, one a line, with their 1-sigma and how it was computed.
std::string ParameterTable(const IntrinsicsCalibrationResult& result) {
  std::string table = "  parameter          value       1-sigma\n";
  const auto out = std::back_inserter(table);
  for (const ParameterRow& row : ParameterRows(result)) {
    if (row.has_sigma) {
      fmt::format_to(out, "  {:<9} {:>14.6f} {:>13.6f} {}\n", row.name, row.value, row.sigma,
                     row.unit);
    } else {
      fmt::format_to(out, "  {:<9} {:>14.6f} {:>13} {}\n", row.name, row.value, "-", row.unit);
    }
  }
  if (result.camera.intrinsics_covariance) {
    fmt::format_to(out,
                   "  (1-sigma from the fit's Jacobian, the board poses marginalised, scaled by "
                   "the residual variance: s = {:.4f} px per axis)\n",
                   result.residual_sigma_px);
  } else {
    table += "  (no 1-sigma: the views do not determine the intrinsics' covariance)\n";
  }
  return table;
}

int CoefficientCount(IntrinsicsModel model) {
  return model == IntrinsicsModel::kRational ? 8 : model == IntrinsicsModel::kRadTan ? 5 : 4;
}

void FillCamera(const Solution& solution, cv::Size image_size, IntrinsicsModel model,
                CameraIntrinsics* camera) {
  camera->width = image_size.width;
  camera->height = image_size.height;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) camera->K(r, c) = solution.K.at<double>(r, c);
  }
  camera->distortion_model = model == IntrinsicsModel::kEquidistant ? DistortionModel::kEquidistant
                                                                    : DistortionModel::kRadTan;
  // With CALIB_RATIONAL_MODEL OpenCV hands back 14 coefficients, the last 6 (thin prism,
  // tilt) zero as they were not asked for: keep the model's own.
  const int count =
      std::min(CoefficientCount(model), static_cast<int>(solution.distortion.total()));
  camera->distortion.resize(count);
  for (int i = 0; i < count; ++i) camera->distortion(i) = solution.distortion.at<double>(i);
}

}  // namespace

constexpr EnumNames<IntrinsicsModel, IntrinsicsModel::kEquidistant> kIntrinsicsModelNames = {
    "radtan", "rational", "equidistant"};

const char* ToString(IntrinsicsModel model) {
  return kIntrinsicsModelNames.NameOf(model, "unknown");
}

bool IntrinsicsCalibrationOptions::IsValid(std::string* why) const {
  if (min_views < 3) {
    *why = fmt::format("min_views must be >= 3 (Zhang's method needs 3 views of a plane), got {}",
                       min_views);
    return false;
  }
  if (!(outlier_factor > 1.0)) {
    *why = fmt::format("outlier_factor must be > 1, got {:f}", outlier_factor);
    return false;
  }
  if (hold_k3 && model == IntrinsicsModel::kEquidistant) {
    *why = "hold_k3 is not available with the equidistant model (its k3 is another term)";
    return false;
  }
  if (fix_aspect_ratio && model == IntrinsicsModel::kEquidistant) {
    *why =
        "fix_aspect_ratio is not available with the equidistant model (cv::fisheye has no "
        "such option)";
    return false;
  }
  if (!(min_orientation_difference_deg >= 0) || min_distinct_orientations < 1 ||
      !(min_tilt_deg >= 0)) {
    *why = "the observability limits must be >= 0 deg and at least 1 distinct orientation";
    return false;
  }
  return true;
}

namespace {

/// Every view's report before solving: name and corners.
std::vector<ViewReport> ViewReportsOf(const std::vector<CalibrationView>& views) {
  std::vector<ViewReport> reports;
  for (const auto& view : views) {
    ViewReport report;
    report.name = view.name;
    report.points = static_cast<int>(view.image_points.size());
    report.corners_px = view.image_points;
    reports.push_back(std::move(report));
  }
  return reports;
}

/// Records the first solution (all views) in each view's report and returns the names of
/// the views whose RMS exceeds outlier_factor x the median.
std::vector<std::string> RecordSolutionOnEveryView(const std::vector<CalibrationView>& views,
                                                   const Solution& solution,
                                                   const IntrinsicsCalibrationOptions& options,
                                                   IntrinsicsCalibrationResult* result) {
  result->median_view_rms_px = Median(solution.view_rms_px);
  const double limit = options.outlier_factor * result->median_view_rms_px;
  result->outlier_limit_px = limit;
  std::vector<std::string> outliers;
  for (size_t i = 0; i < views.size(); ++i) {
    ViewReport& view = result->views[i];
    view.rms_px = solution.view_rms_px[i];
    view.tilt_deg = TiltDeg(solution.board_normals[i]);
    view.outlier = solution.view_rms_px[i] > limit;
    view.corners_px = views[i].image_points;
    view.residuals_px = solution.residuals_px[i];
    if (view.outlier) outliers.push_back(views[i].name);
  }
  return outliers;
}

/// Solves again without the outlier views, unless too few would remain (then says so in
/// result->message and keeps the first solution). False when the second solve fails.
bool RecalibrateWithoutOutliers(const std::vector<CalibrationView>& views, cv::Size image_size,
                                const IntrinsicsCalibrationOptions& options, size_t outliers,
                                Solution* solution, IntrinsicsCalibrationResult* result) {
  std::vector<const CalibrationView*> kept;
  for (size_t i = 0; i < views.size(); ++i) {
    if (!result->views[i].outlier) kept.push_back(&views[i]);
  }
  if (static_cast<int>(kept.size()) < options.min_views) {
    result->message =
        fmt::format("outliers kept: dropping them would leave {} view(s), fewer than {}",
                    kept.size(), options.min_views);
    return true;
  }
  if (!Solve(kept, image_size, options, solution, &result->message)) return false;
  size_t k = 0;
  for (auto& view : result->views) {
    view.used = !view.outlier;
    if (!view.used) continue;
    view.rms_px = solution->view_rms_px[k];
    view.tilt_deg = TiltDeg(solution->board_normals[k]);
    view.residuals_px = solution->residuals_px[k];
    ++k;
  }
  result->message = fmt::format("dropped {} outlier view(s) and recalibrated", outliers);
  return true;
}

/// The camera file's content from the solution, with the intrinsics' covariance (written to
/// the camera YAML for the identification's predicted accuracy; without it the file claims
/// nothing).
void FillCameraWithCovariance(const Solution& solution, cv::Size image_size,
                              const IntrinsicsCalibrationOptions& options,
                              IntrinsicsCalibrationResult* result) {
  result->rms_px = solution.rms_px;
  result->views_used = static_cast<int>(std::count_if(result->views.begin(), result->views.end(),
                                                      [](const auto& v) { return v.used; }));
  FillCamera(solution, image_size, options.model, &result->camera);
  result->camera.avg_reprojection_error = result->rms_px;
  // k3 comes after fx, fy, cx, cy and k1 k2 p1 p2.
  constexpr int kK3Index = 8;
  const std::vector<int> held = options.hold_k3 ? std::vector<int>{kK3Index} : std::vector<int>{};
  if (const auto covariance = IntrinsicsCovarianceOf(result->camera, solution.fits,
                                                     options.fix_aspect_ratio, held)) {
    result->camera.intrinsics_covariance = covariance->covariance;
    result->residual_sigma_px = covariance->sigma_px;
  }
}

IntrinsicsCalibrationResult CalibrateOnce(const std::vector<CalibrationView>& views,
                                          cv::Size image_size,
                                          const IntrinsicsCalibrationOptions& options) {
  IntrinsicsCalibrationResult result;
  result.model = options.model;
  if (!options.IsValid(&result.message)) {
    result.status = IntrinsicsCalibrationResult::Status::kInvalidOptions;
    return result;
  }
  result.views = ViewReportsOf(views);
  if (static_cast<int>(views.size()) < options.min_views) {
    result.status = IntrinsicsCalibrationResult::Status::kTooFewViews;
    result.message = fmt::format("{} view(s) with the board, expected at least {}", views.size(),
                                 options.min_views);
    return result;
  }
  std::vector<const CalibrationView*> used;
  for (const auto& view : views) used.push_back(&view);
  Solution solution;
  if (!Solve(used, image_size, options, &solution, &result.message)) return result;
  const std::vector<std::string> outliers =
      RecordSolutionOnEveryView(views, solution, options, &result);
  if (options.drop_outliers && !outliers.empty() &&
      !RecalibrateWithoutOutliers(views, image_size, options, outliers.size(), &solution,
                                  &result)) {
    return result;
  }
  FillCameraWithCovariance(solution, image_size, options, &result);
  const std::string degenerate = FocalLengthObservability(solution, options, &result);
  if (!degenerate.empty()) {
    result.status = IntrinsicsCalibrationResult::Status::kDegenerateViews;
    result.message = degenerate;
    return result;
  }
  // A distortion fit on corners that leave much of the image empty can fold inside the
  // image (issue 42 point 19: 291 px from the centre on a real 8-view set, 28-36 % of the
  // image without a valid ray); the camera file's reader would refuse it, so refuse it here.
  if (const std::string fold = CameraModel(result.camera).FoldInsideImage(); !fold.empty()) {
    result.status = IntrinsicsCalibrationResult::Status::kFoldingDistortion;
    result.message = fold +
                     ". Add views with the board near the image's corners and edges, where the "
                     "fit has no corner to hold the distortion";
    return result;
  }
  result.status = IntrinsicsCalibrationResult::Status::kOk;
  return result;
}

}  // namespace

IntrinsicsCalibrationResult CalibrateIntrinsics(const std::vector<CalibrationView>& views,
                                                cv::Size image_size,
                                                const IntrinsicsCalibrationOptions& options) {
  IntrinsicsCalibrationResult result = CalibrateOnce(views, image_size, options);
  if (result.status != IntrinsicsCalibrationResult::Status::kFoldingDistortion ||
      options.model != IntrinsicsModel::kRadTan || options.hold_k3) {
    return result;
  }
  // The r^6 term is the one that bends the model back inside the image when the corners
  // leave its edge empty (a real 30-view set: folding 404 px from the centre, the image
  // reaching 407 px; tests/calibration/real_frames_test.cpp). Held at 0, as OpenCV's users
  // often do, the others may describe the lens; if they fold too, the first refusal stands.
  IntrinsicsCalibrationOptions without_k3 = options;
  without_k3.hold_k3 = true;
  IntrinsicsCalibrationResult held = CalibrateOnce(views, image_size, without_k3);
  if (!held.ok()) return result;
  const std::string fold = result.message.substr(0, result.message.find(". Add views"));
  const std::string note = "k3 held at 0: with it free, " + fold;
  held.message = held.message.empty() ? note : note + "; " + held.message;
  return held;
}

std::string IntrinsicsCalibrationResult::Report() const {
  std::string report;
  const auto out = std::back_inserter(report);
  if (!ok()) {
    fmt::format_to(out, "calibration failed: {}\n", message);
    if (status != Status::kDegenerateViews && status != Status::kFoldingDistortion) return report;
    report += "(refused solution, for diagnosis only:)\n";
  }
  fmt::format_to(out, "image {}x{}, {} of {} views used, model {}, distortion ({})\n", camera.width,
                 camera.height, views_used, views.size(), ToString(model), DistortionNames(*this));
  report += ParameterTable(*this);
  fmt::format_to(out, "RMS reprojection error {:.4f} px (median per view {:.4f} px)\n", rms_px,
                 median_view_rms_px);
  fmt::format_to(out, "{} distinct board orientation(s), largest tilt {:.1f} deg\n",
                 distinct_orientations, max_tilt_deg);
  for (const auto& view : views) {
    fmt::format_to(out, "  {}: {} points, RMS {:.4f} px, tilt {:.3f} deg", view.name, view.points,
                   view.rms_px, view.tilt_deg);
    if (view.outlier) fmt::format_to(out, "  OUTLIER (first RMS > {:.3f} px)", outlier_limit_px);
    report += view.used ? "\n" : ", dropped\n";
  }
  if (!message.empty() && ok()) fmt::format_to(out, "{}\n", message);
  return report;
}

}  // namespace h4::cam

// Figures and overlay of one camera frame; see frame_check.h.
#include "firmware/cli/frame_check.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "firmware/pose/pose_estimator.h"

namespace h4::cam {
namespace {

std::vector<cv::Point2f> CornerPixels(const BoardDetection& detection) {
  std::vector<cv::Point2f> pixels;
  pixels.reserve(detection.corners.size());
  for (const CornerObservation& c : detection.corners) {
    pixels.emplace_back(static_cast<float>(c.uv.x()), static_cast<float>(c.uv.y()));
  }
  return pixels;
}

double VarianceOfLaplacian(const cv::Mat& image) {
  cv::Mat laplacian;
  cv::Laplacian(image, laplacian, CV_64F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(laplacian, mean, stddev);
  return stddev[0] * stddev[0];
}

/// The board's bounding box (grown by 5 % of its size, kept in the image), or the image.
cv::Rect BoardRegion(const cv::Mat& image, const std::vector<cv::Point2f>& corners) {
  const cv::Rect whole(0, 0, image.cols, image.rows);
  if (corners.size() < 4) return whole;
  cv::Rect box = cv::boundingRect(corners);
  const int grow_x = box.width / 20 + 1, grow_y = box.height / 20 + 1;
  box = cv::Rect(box.x - grow_x, box.y - grow_y, box.width + 2 * grow_x, box.height + 2 * grow_y);
  box &= whole;
  return box.area() >= 9 ? box : whole;
}

double Coverage(const cv::Mat& image, const std::vector<cv::Point2f>& corners) {
  if (corners.size() < 3) return 0.0;
  std::vector<cv::Point2f> hull;
  cv::convexHull(corners, hull);
  return cv::contourArea(hull) / (static_cast<double>(image.cols) * image.rows);
}

int TagsOnBoard(const BoardModel& board) {
  if (!board.is_aprilgrid()) return 0;
  const AprilGridSpec& grid = std::get<AprilGridSpec>(board.spec());
  return grid.rows * grid.cols;
}

}  // namespace

FrameFigures CheckFrame(const cv::Mat& image, const BoardDetector& detector,
                        const CameraModel& camera, BoardDetection* detection_out) {
  const BoardDetection detection = detector.Detect(image);
  const std::vector<cv::Point2f> corners = CornerPixels(detection);
  FrameFigures figures;
  figures.status = detection.status;
  figures.chessboard = !detector.board().is_aprilgrid();
  figures.tags = detection.tags;
  figures.tags_total = TagsOnBoard(detector.board());
  figures.corners = static_cast<int>(detection.corners.size());
  figures.corners_total = detector.board().corner_count();
  if (!detection.corners.empty()) {
    const PoseEstimate pose = EstimatePose(detection.corners, camera);
    if (pose.ok()) figures.rms_px = pose.rms_px;
  }
  figures.sharpness = VarianceOfLaplacian(image(BoardRegion(image, corners)));
  figures.mean_level = cv::mean(image)[0];
  figures.saturated_fraction =
      static_cast<double>(cv::countNonZero(image >= 255)) / static_cast<double>(image.total());
  figures.coverage = Coverage(image, corners);
  if (detection_out != nullptr) *detection_out = detection;
  return figures;
}

namespace {

/// "36/36 tags, 144/144 corners"; a chessboard has no tags to count: "chessboard: 54/54
/// corners" (not "0/0 tags").
std::string FeaturesFound(const FrameFigures& f) {
  if (f.chessboard) return fmt::format("chessboard: {}/{} corners", f.corners, f.corners_total);
  return fmt::format("{}/{} tags, {}/{} corners", f.tags, f.tags_total, f.corners, f.corners_total);
}

// Each tag the detection expected wholly in the image but left out: its predicted outline in
// red, with the reason ("not found", "failed code", "failed refinement") at its centre.
void DrawMissedTags(const BoardDetection& detection, cv::Mat* overlay) {
  for (const MissedTag& miss : detection.missed) {
    std::vector<cv::Point> outline;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& uv : miss.corners_px) {
      outline.emplace_back(static_cast<int>(std::lround(uv.x())),
                           static_cast<int>(std::lround(uv.y())));
      centre += 0.25 * uv;
    }
    cv::polylines(*overlay, outline, /*isClosed=*/true, cv::Scalar(0, 0, 255), 1);
    const std::string label = fmt::format("{} {}", miss.tag_id, ToString(miss.why));
    cv::putText(*overlay, label,
                cv::Point(static_cast<int>(centre.x()) - 20, static_cast<int>(centre.y())),
                cv::FONT_HERSHEY_SIMPLEX, 0.3, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
  }
}

}  // namespace

std::string FormatFrameFigures(const FrameFigures& f) {
  const std::string rms = f.rms_px ? fmt::format("rms {:.3f} px", *f.rms_px) : "rms -";
  return fmt::format(
      "{}{}, {}, {}, sharpness {:.0f}, mean level {:.1f}, saturated {:.2f} %, coverage {:.1f} %",
      f.status == BoardDetection::Status::kNoBoard ? "" : "board ", ToString(f.status),
      FeaturesFound(f), rms, f.sharpness, f.mean_level, 100.0 * f.saturated_fraction,
      100.0 * f.coverage);
}

cv::Mat DrawFrameFigures(const cv::Mat& image, const BoardDetection& detection,
                         const FrameFigures& figures) {
  cv::Mat overlay;
  cv::cvtColor(image, overlay, cv::COLOR_GRAY2BGR);
  const std::vector<cv::Point2f> corners = CornerPixels(detection);
  if (corners.size() >= 3) {
    std::vector<cv::Point2f> hull;
    cv::convexHull(corners, hull);
    std::vector<cv::Point> polygon(hull.begin(), hull.end());
    cv::polylines(overlay, polygon, /*isClosed=*/true, cv::Scalar(0, 255, 255), 2);
  }
  for (const cv::Point2f& p : corners) {
    cv::drawMarker(overlay, p, cv::Scalar(0, 255, 0), cv::MARKER_CROSS, 9, 1);
  }
  DrawMissedTags(detection, &overlay);
  const cv::Scalar colour =
      figures.status == BoardDetection::Status::kOk ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 255);
  cv::rectangle(overlay, cv::Rect(0, 0, overlay.cols, 26), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(overlay, FormatFrameFigures(figures), cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX,
              0.45, colour, 1, cv::LINE_AA);
  return overlay;
}

void RequireTheCameraFilesSize(const Frame& frame, const CameraIntrinsics& camera,
                               const std::string& camera_path) {
  if (frame.image.cols == camera.width && frame.image.rows == camera.height) return;
  throw std::runtime_error(fmt::format("{}: image is {}x{}, the camera file {} says {}x{}",
                                       frame.origin.empty() ? "frame" : frame.origin,
                                       frame.image.cols, frame.image.rows, camera_path,
                                       camera.width, camera.height));
}

}  // namespace h4::cam

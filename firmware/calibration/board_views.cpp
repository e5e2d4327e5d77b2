// Board detection for intrinsics calibration; see board_views.h.
#include "firmware/calibration/board_views.h"

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "firmware/detection/apriltag_detector.h"
#include "firmware/detection/x_corner_refinement.h"

namespace h4::cam {

BoardViewFinder::BoardViewFinder(const BoardSpec& board, const BoardViewOptions& options)
    : model_(board), options_(options) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    AprilTagOptions tag_options;
    tag_options.family = grid->tag_family;
    tag_options.border_cells = grid->design().border_cells;
    tag_options.open_contacts_px = grid->design().corner_squares ? 1 : 0;
    tag_detector_ = std::make_unique<AprilTagDetector>(tag_options);
    if (!tag_detector_->ok()) {
      error_ = tag_detector_->error();
    } else if (grid->design().corner_squares) {
      x_radius_of_side_ =
          XRadiusOfSide(tag_options.border_cells, tag_detector_->border_cells(), grid->tag_spacing);
    }
  }
}

BoardViewFinder::~BoardViewFinder() = default;

std::optional<CalibrationView> BoardViewFinder::Find(const cv::Mat& grey, const std::string& name,
                                                     std::string* why) const {
  if (grey.empty() || grey.type() != CV_8UC1) {
    *why = "expected an 8-bit grey image";
    return std::nullopt;
  }
  auto view = model_.is_aprilgrid() ? FindAprilGrid(grey, why) : FindChessboard(grey, why);
  if (view) view->name = name;
  return view;
}

std::optional<CalibrationView> BoardViewFinder::FindChessboard(const cv::Mat& grey,
                                                               std::string* why) const {
  const auto& board = std::get<CheckerboardSpec>(model_.spec());
  const cv::Size pattern(board.cols, board.rows);
  std::vector<cv::Point2f> corners;
  // The flags of OpenCV's calibration sample.
  const int flags =
      cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_FAST_CHECK | cv::CALIB_CB_NORMALIZE_IMAGE;
  // Bounded: asked for a count the image does not show, the classic detector's search
  // on a full-size view took over 70 s (chessboard_corners.h).
  if (!FindChessboardCornersBounded(grey, pattern, flags, &corners, &work_)) {
    *why = fmt::format("no {}x{} chessboard (inner corners) found", board.cols, board.rows);
    return std::nullopt;
  }
  const cv::Size window(options_.subpix_half_window, options_.subpix_half_window);
  cv::cornerSubPix(grey, corners, window, cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 1e-4));
  CalibrationView view;
  view.image_points = std::move(corners);
  // findChessboardCorners returns the corners row by row, as the board model numbers them.
  for (const auto& p : model_.corners()) {
    view.object_points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
  }
  return view;
}

std::optional<CalibrationView> BoardViewFinder::FindAprilGrid(const cv::Mat& grey,
                                                              std::string* why) const {
  CalibrationView view;
  int tags = 0;
  cv::Mat grey32;
  if (x_radius_of_side_ > 0) grey.convertTo(grey32, CV_32F);
  for (TagDetection& tag : tag_detector_->Detect(grey)) {
    if (model_.TagCornerId(tag.id, 0) < 0) continue;  // a tag of another board
    // Kalibr's board: every corner is an X-corner, refined as such (or the tag dropped).
    if (x_radius_of_side_ > 0 &&
        !RefineXCorners(grey32, XCornerOptions{}, x_radius_of_side_, &tag.corners_px)) {
      continue;
    }
    ++tags;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = *model_.Corner(model_.TagCornerId(tag.id, k));
      view.image_points.emplace_back(static_cast<float>(tag.corners_px[k].x()),
                                     static_cast<float>(tag.corners_px[k].y()));
      view.object_points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
    }
  }
  if (tags < options_.min_tags) {
    *why =
        fmt::format("{} tag(s) of the board found, expected at least {}", tags, options_.min_tags);
    return std::nullopt;
  }
  return view;
}

}  // namespace h4::cam

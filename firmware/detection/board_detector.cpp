// Board detection; see board_detector.h.
#include "firmware/detection/board_detector.h"

#include <opencv2/imgproc.hpp>

#include "common/camera/camera_model.h"
#include "firmware/detection/chessboard_corners.h"

namespace h4::cam {

const char* ToString(BoardDetection::Status status) {
  switch (status) {
    case BoardDetection::Status::kOk:
      return "ok";
    case BoardDetection::Status::kPartial:
      return "partial";
    case BoardDetection::Status::kNoBoard:
      return "no board";
  }
  return "?";
}

BoardDetector::BoardDetector(const BoardSpec& board, const CameraIntrinsics& camera,
                             const DetectorOptions& options)
    : board_(board), options_(options), width_(camera.width), height_(camera.height) {
  const CameraModel model(camera);
  if (!model.valid() || width_ <= 0 || height_ <= 0) {
    error_ = "camera intrinsics invalid (size, focal length or distortion count)";
    return;
  }
  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    AprilTagOptions tag_options = options.apriltag;
    tag_options.family = grid->tag_family;
    apriltag_ = std::make_unique<AprilTagDetector>(tag_options);
    if (!apriltag_->ok()) {
      error_ = apriltag_->error();
      return;
    }
    if (options.refinement == CornerRefinement::kEdgeFit) {
      options_.edge_fit.border_cells = apriltag_->border_cells();
      ideal_map_ = std::make_unique<IdealPixelMap>(model);
    }
  }
}

BoardDetector::~BoardDetector() = default;

BoardDetection BoardDetector::Detect(const cv::Mat& image) const {
  if (!ok() || image.empty() || image.channels() != 1 || image.cols != width_ ||
      image.rows != height_) {
    return {};
  }
  cv::Mat image8, image32;
  if (image.type() == CV_8UC1) {
    image8 = image;
    image.convertTo(image32, CV_32F);
  } else if (image.type() == CV_32FC1) {
    image32 = image;
    image.convertTo(image8, CV_8U);  // rounded, saturated
  } else {
    return {};
  }
  BoardDetection detection =
      board_.is_aprilgrid() ? DetectAprilGrid(image8, image32) : DetectChessboard(image8, image32);
  const int n = static_cast<int>(detection.corners.size());
  detection.status = n == 0                     ? BoardDetection::Status::kNoBoard
                     : n < options_.min_corners ? BoardDetection::Status::kPartial
                                                : BoardDetection::Status::kOk;
  return detection;
}

BoardDetection BoardDetector::DetectAprilGrid(const cv::Mat& image8, const cv::Mat& image32) const {
  BoardDetection detection;
  std::vector<TagDetection> tags = apriltag_->Detect(image8);
  // A tag id seen twice is a misdecode or a second board: trust neither.
  std::vector<int> seen(static_cast<size_t>(board_.corner_count() / 4), 0);
  for (const TagDetection& tag : tags) {
    const int first = board_.TagCornerId(tag.id, 0);
    if (first >= 0) ++seen[static_cast<size_t>(first / 4)];
  }
  std::vector<cv::Point2f> subpix;
  for (TagDetection& tag : tags) {
    const int first = board_.TagCornerId(tag.id, 0);
    if (first < 0 || seen[static_cast<size_t>(first / 4)] != 1) continue;
    // Only edge-fitted corners know their sides, hence how they move under erosion.
    std::array<Eigen::Vector2d, 4> erosion_px{};
    for (Eigen::Vector2d& e : erosion_px) e.setZero();
    if (options_.refinement == CornerRefinement::kEdgeFit &&
        !RefineQuadCorners(image32, *ideal_map_, options_.edge_fit, &tag.corners_px, &erosion_px)) {
      ++detection.tags_rejected;
      continue;
    }
    ++detection.tags;
    for (int k = 0; k < 4; ++k) {
      CornerObservation corner;
      corner.id = first + k;
      corner.p_TQ = board_.corners()[static_cast<size_t>(corner.id)];
      corner.uv = tag.corners_px[static_cast<size_t>(k)];
      corner.erosion_px = erosion_px[static_cast<size_t>(k)];
      corner.edge_group = first / 4;
      detection.corners.push_back(corner);
      subpix.emplace_back(static_cast<float>(corner.uv.x()), static_cast<float>(corner.uv.y()));
    }
  }
  if (options_.refinement == CornerRefinement::kCornerSubPix && !subpix.empty()) {
    const int w = options_.subpix_half_window;
    cv::cornerSubPix(image32, subpix, cv::Size(w, w), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 1e-4));
    for (size_t i = 0; i < subpix.size(); ++i) {
      detection.corners[i].uv = Eigen::Vector2d(subpix[i].x, subpix[i].y);
    }
  }
  return detection;
}

BoardDetection BoardDetector::DetectChessboard(const cv::Mat& image8,
                                               const cv::Mat& image32) const {
  BoardDetection detection;
  const auto& spec = std::get<CheckerboardSpec>(board_.spec());
  std::vector<Eigen::Vector2d> uv;
  if (!FindChessboardCorners(image8, image32, spec, options_.subpix_half_window, &uv)) {
    return detection;
  }
  for (size_t i = 0; i < uv.size(); ++i) {
    CornerObservation corner;
    corner.id = static_cast<int>(i);
    corner.p_TQ = board_.corners()[i];
    corner.uv = uv[i];
    detection.corners.push_back(corner);
  }
  return detection;
}

}  // namespace h4::cam

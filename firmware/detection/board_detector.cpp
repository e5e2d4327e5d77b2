// Board detection; see board_detector.h.
#include "firmware/detection/board_detector.h"

#include <algorithm>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "common/camera/camera_model.h"
#include "common/formats/image_size.h"
#include "common/text/enum_names.h"
#include "firmware/detection/chessboard_corners.h"

namespace h4::cam {

constexpr EnumNames<BoardDetection::Status, BoardDetection::Status::kNoBoard>
    kBoardDetectionStatusNames = {"ok", "partial", "no board"};

const char* ToString(BoardDetection::Status status) {
  return kBoardDetectionStatusNames.NameOf(status);
}

BoardDetector::BoardDetector(const BoardSpec& board, const CameraIntrinsics& camera,
                             const DetectorOptions& options)
    : board_(board),
      options_(options),
      camera_(camera),
      width_(camera.width),
      height_(camera.height) {
  const CameraModel model(camera);
  if (!model.valid()) {
    error_ = "camera intrinsics invalid (focal length or distortion count)";
    return;
  }
  // The sizes libapriltag and the chessboard detector handle (image_size.h: an image 4 px
  // high crashes libapriltag).
  if (const std::string problem = ImageSizeProblem(width_, height_); !problem.empty()) {
    error_ = "camera image size " + problem;
    return;
  }
  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    const AprilTagOptions tag_options = AprilTagOptionsFor(*grid, options.apriltag);
    apriltag_ = std::make_unique<AprilTagDetector>(tag_options);
    if (!apriltag_->ok()) {
      error_ = apriltag_->error();
      return;
    }
    code_reader_ = std::make_unique<TagCodeReader>(board_, *grid);
    if (grid->design().corner_squares) {
      x_radius_of_side_ =
          XRadiusOfSide(tag_options.border_cells, apriltag_->border_cells(), grid->tag_spacing);
    }
    std::string why;
    if (x_radius_of_side_ > 0 && !options_.x_corner.IsValid(&why)) {
      error_ = "x_corner options: " + why;
      return;
    }
    if (options.refinement == CornerRefinement::kEdgeFit) {
      options_.edge_fit.tag_width_cells = apriltag_->border_cells();
      options_.edge_fit.border_thickness_cells = grid->design().border_cells;
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
  // Kalibr's board: candidates from both searches (apriltag_detector.h open_contacts_px),
  // per tag the one with the most X-corners that check out is kept.
  std::vector<TagDetection> tags =
      x_radius_of_side_ > 0 ? apriltag_->DetectCandidates(image8) : apriltag_->Detect(image8);
  // A tag id seen twice in one search is a misdecode or a second board: trust neither.
  const size_t tag_count = static_cast<size_t>(board_.corner_count() / 4);
  std::vector<int> seen(2 * tag_count, 0);
  for (const TagDetection& tag : tags) {
    const int first = board_.TagCornerId(tag.id, 0);
    if (first >= 0) ++seen[static_cast<size_t>(first / 4) * 2 + (tag.search > 0 ? 1 : 0)];
  }
  for (size_t index = 0; index < tag_count; ++index) {
    if (seen[2 * index] > 1 || seen[2 * index + 1] > 1) ++detection.ids_seen_twice;
  }
  // Per tag, the best candidate (RefinedTag::BetterThan; the first of equals).
  std::vector<std::optional<RefinedTag>> best(tag_count);
  std::vector<char> candidate(tag_count, 0);
  for (TagDetection& tag : tags) {
    const int first = board_.TagCornerId(tag.id, 0);
    if (first < 0) continue;
    const size_t index = static_cast<size_t>(first / 4);
    if (seen[index * 2 + (tag.search > 0 ? 1 : 0)] != 1) continue;
    if (best[index] && best[index]->edge_fitted) continue;  // none better
    candidate[index] = 1;
    std::optional<RefinedTag> refined = RefineTag(image32, &tag);
    if (refined && (!best[index] || refined->BetterThan(*best[index]))) best[index] = refined;
  }
  RecoverMissedTags(image32, &best, &detection);
  std::vector<cv::Point2f> subpix;
  for (size_t index = 0; index < tag_count; ++index) {
    if (!best[index]) {
      if (candidate[index]) ++detection.tags_rejected;
      continue;
    }
    ++detection.tags;
    const RefinedTag& tag = *best[index];
    const int first = static_cast<int>(index) * 4;
    for (size_t k = 0; k < 4; ++k) {
      if (!tag.refined[k]) continue;  // an X-corner that failed its checks
      CornerObservation corner;
      corner.id = first + static_cast<int>(k);
      corner.p_TQ = board_.corners()[static_cast<size_t>(corner.id)];
      corner.uv = tag.corners_px[k];
      corner.erosion_px = tag.erosion_px[k];
      corner.noise_px = tag.noise_px[k];
      if (tag.edge_fitted) corner.edge_group = first / 4;
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

std::optional<BoardDetector::RefinedTag> BoardDetector::RefineTag(const cv::Mat& image32,
                                                                  TagDetection* tag) const {
  RefinedTag refined;
  for (Eigen::Vector2d& e : refined.erosion_px) e.setZero();
  for (CornerNoisePx& n : refined.noise_px) n.setZero();
  refined.refined = {true, true, true, true};
  // On a board with corner squares every corner is an X-corner: refined on its own first,
  // it places the tag's sides for the edge fit (the quad search's corners of such tags can
  // be 1.4 px inside, apriltag_detector.h open_contacts_px), and it is what a tag whose
  // sides do not fit (a side cut by the image edge, an occluder) keeps.
  const bool edge_fit = options_.refinement == CornerRefinement::kEdgeFit;
  const bool wants_x_corners =
      options_.refinement == CornerRefinement::kXCorner || (edge_fit && x_radius_of_side_ > 0);
  const bool some_x_corners = wants_x_corners && RefineTagXCorners(image32, tag, &refined.refined);
  if (options_.refinement == CornerRefinement::kXCorner && !some_x_corners) return std::nullopt;
  if (edge_fit) {
    // Only edge-fitted corners know their sides, hence how they move under erosion;
    // X-corners do not move under erosion (their directions stay zero).
    std::array<Eigen::Vector2d, 4> fitted = tag->corners_px;
    refined.edge_fitted = RefineQuadCorners(image32, *ideal_map_, options_.edge_fit, &fitted,
                                            &refined.erosion_px, &refined.noise_px);
    if (refined.edge_fitted) {
      tag->corners_px = fitted;
      refined.refined = {true, true, true, true};
    } else if (!some_x_corners) {
      return std::nullopt;
    }
  }
  refined.corners_px = tag->corners_px;
  refined.count =
      static_cast<int>(std::count(refined.refined.begin(), refined.refined.end(), true));
  return refined;
}

bool BoardDetector::RefineTagXCorners(const cv::Mat& image32, TagDetection* tag,
                                      std::array<bool, 4>* refined) const {
  if (x_radius_of_side_ <= 0) return false;  // no corner squares: these are no X-corners
  return RefineEachXCorner(image32, options_.x_corner, x_radius_of_side_, &tag->corners_px,
                           refined) > 0;
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

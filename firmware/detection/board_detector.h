// Finds the calibration board in an (averaged) image and pairs each detected corner with
// its position on the board: AprilTag grids through libapriltag plus sub-pixel
// refinement, chessboards through OpenCV. The output feeds the pose estimator.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_intrinsics.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/detection/apriltag_detector.h"
#include "firmware/detection/corner_observation.h"
#include "firmware/detection/edge_refinement.h"
#include "firmware/detection/ideal_pixel_map.h"
#include "firmware/detection/tag_prediction.h"
#include "firmware/detection/x_corner_refinement.h"

namespace h4::cam {

enum class CornerRefinement {
  kNone,          ///< libapriltag's corners as they come (convention-corrected; on a
                  ///< board with corner squares, tags only the opened second search found
                  ///< have their corners up to 1.4 px inside the tag)
  kCornerSubPix,  ///< cv::cornerSubPix on the averaged image
  kEdgeFit,       ///< blurred-step fit of the tag sides (edge_refinement.h): the most
                  ///< accurate (tests/camera_service/board_detector_test.cpp); on a board with
                  ///< corner squares (Kalibr's) the sides are fitted between the squares, and
                  ///< a tag whose sides do not fit falls back on kXCorner
  kXCorner,       ///< cornerSubPix on each X-corner (x_corner_refinement.h), boards with
                  ///< corner squares only
};

struct DetectorOptions {
  AprilTagOptions apriltag;
  CornerRefinement refinement = CornerRefinement::kEdgeFit;
  EdgeFitOptions edge_fit;
  XCornerOptions x_corner;
  /// AprilTag grids: the tags libapriltag missed, predicted from the found ones' pose
  /// through the camera model and verified by their code (tag_prediction.h).
  TagPredictionOptions prediction;
  int subpix_half_window = 5;  ///< cornerSubPix window (2n+1)^2, px (chessboard too)
  /// Fewer corners than this: status kPartial (the pose would be unreliable).
  int min_corners = kMinBoardCorners;  ///< the board reader refuses smaller boards
};

struct BoardDetection {
  /// Named by ToString, in this order (board_detector.cpp).
  enum class Status { kOk, kPartial, kNoBoard };
  Status status = Status::kNoBoard;
  std::vector<CornerObservation> corners;
  int tags = 0;           ///< AprilTag grid: tags used
  int tags_rejected = 0;  ///< tags whose refinement failed (dropped)
  /// AprilTag grid: ids decoded more than once in one search (two boards in view, or a
  /// misdecode), every detection of them dropped; said in the measurement's message.
  int ids_seen_twice = 0;
  /// AprilTag grid: tags among `tags` that the quad search missed and the prediction found
  /// (tag_prediction.h).
  int tags_predicted = 0;
  /// AprilTag grid: tags predicted wholly inside the image but not in the detection, and why
  /// (empty when every tag was found or too few were to predict from).
  std::vector<MissedTag> missed;
};

const char* ToString(BoardDetection::Status status);

class BoardDetector {
 public:
  BoardDetector(const BoardSpec& board, const CameraIntrinsics& camera,
                const DetectorOptions& options = {});
  ~BoardDetector();

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const BoardModel& board() const { return board_; }
  const DetectorOptions& options() const { return options_; }

  /// Detects the board in a CV_8UC1 or CV_32FC1 image (grey levels 0..255).
  BoardDetection Detect(const cv::Mat& image) const;

 private:
  BoardDetection DetectAprilGrid(const cv::Mat& image8, const cv::Mat& image32) const;
  BoardDetection DetectChessboard(const cv::Mat& image8, const cv::Mat& image32) const;
  /// One tag's corners after refinement, with what each corner knows of its errors.
  struct RefinedTag {
    std::array<Eigen::Vector2d, 4> corners_px;
    std::array<Eigen::Vector2d, 4> erosion_px;
    std::array<CornerNoisePx, 4> noise_px;
    std::array<bool, 4> refined;  ///< false: an X-corner that failed (left out)
    int count = 0;                ///< corners refined
    bool edge_fitted = false;
    /// Edge-fitted sides first (hundreds of pixels each against an X-corner's window),
    /// then more refined corners.
    bool BetterThan(const RefinedTag& other) const {
      return edge_fitted != other.edge_fitted ? edge_fitted : count > other.count;
    }
  };
  /// Refines a candidate's corners with the detector's refinement; nullopt drops it.
  std::optional<RefinedTag> RefineTag(const cv::Mat& image32, TagDetection* tag) const;
  /// X-corner refinement of one tag's corners (Kalibr layout), each on its own
  /// (`refined`); false (none could be) drops the tag.
  bool RefineTagXCorners(const cv::Mat& image32, TagDetection* tag,
                         std::array<bool, 4>* refined) const;
  /// Adds to `best` the tags the prediction recovers (board_detector_prediction.cpp).
  void RecoverMissedTags(const cv::Mat& image32, std::vector<std::optional<RefinedTag>>* best,
                         BoardDetection* detection) const;
  /// X_CT fitted to the found tags, leaving out tags that disagree with the others.
  bool FitPoseToFoundTags(const std::vector<std::optional<RefinedTag>>& best,
                          RigidTransform* X_CT) const;
  /// Tags missing from `best` checked at their place under X_CT: the verified and refined
  /// ones added to `best` (their number returned), the others in `missed`.
  int PredictMissingTags(const cv::Mat& image32, const RigidTransform& X_CT,
                         std::vector<std::optional<RefinedTag>>* best,
                         std::vector<MissedTag>* missed) const;

  BoardModel board_;
  DetectorOptions options_;
  CameraModel camera_;
  std::unique_ptr<TagCodeReader> code_reader_;  // AprilTag grids
  std::unique_ptr<AprilTagDetector> apriltag_;
  std::unique_ptr<IdealPixelMap> ideal_map_;
  double x_radius_of_side_ = 0;  // X-corner radius / tag side (Kalibr layout)
  int width_ = 0, height_ = 0;
  std::string error_;
};

}  // namespace h4::cam

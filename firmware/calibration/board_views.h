// Finding a calibration board in an image for intrinsics calibration: the board corners
// seen (image points, OpenCV pixel convention) paired with their positions on the board
// (p_TQ, board_model.h). Chessboards through OpenCV (findChessboardCorners on a copy of at
// most VGA size, chessboard_corners.h, then cornerSubPix at full size with an 11x11 window,
// as OpenCV's calibration sample), AprilTag grids through the firmware's AprilTag
// detector (every tag of the board that is seen gives its 4 corners).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/board/board_model.h"
#include "firmware/detection/chessboard_corners.h"

namespace h4::cam {

class AprilTagDetector;

/// One image in which the board was found.
struct CalibrationView {
  std::string name;                        ///< image file name (for reports)
  std::vector<cv::Point2f> image_points;   ///< px
  std::vector<cv::Point3f> object_points;  ///< p_TQ, m (z = 0)
};

struct BoardViewOptions {
  /// Chessboard: cornerSubPix winSize, px (half the side of the search window, so 11 searches
  /// 23 x 23 pixels): Size(11, 11) as in OpenCV's calibration sample.
  int subpix_half_window = 11;
  /// AprilTag grid: fewer tags than this in an image and the image is not used (few
  /// tags close together constrain the distortion poorly).
  int min_tags = 4;
};

class BoardViewFinder {
 public:
  explicit BoardViewFinder(const BoardSpec& board, const BoardViewOptions& options = {});
  ~BoardViewFinder();
  BoardViewFinder(const BoardViewFinder&) = delete;
  BoardViewFinder& operator=(const BoardViewFinder&) = delete;

  /// False (with error()) when the board cannot be detected at all (unsupported family).
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  /// The board in a CV_8UC1 image, or nullopt (with `why` saying what was missing).
  std::optional<CalibrationView> Find(const cv::Mat& grey, const std::string& name,
                                      std::string* why) const;
  /// The chessboard detector's work over every Find() so far (tests bound it).
  const ChessboardWork& chessboard_work() const { return work_; }

 private:
  std::optional<CalibrationView> FindChessboard(const cv::Mat& grey, std::string* why) const;
  std::optional<CalibrationView> FindAprilGrid(const cv::Mat& grey, std::string* why) const;

  BoardModel model_;
  BoardViewOptions options_;
  std::unique_ptr<AprilTagDetector> tag_detector_;
  double x_radius_of_side_ = 0;  // Kalibr's board: X-corner radius / tag side
  std::string error_;
  mutable ChessboardWork work_;  // a counter only: Find() stays logically const
};

}  // namespace h4::cam

// One measurement of the board by the camera module: the pose X_CT with its covariance
// and quality figures, or the reason there is none. The camera service turns it into a
// board_pose_t (messages/), `h4cam measure` into a row of the offline board poses CSV.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_pose_status.h"
#include "common/geometry/rigid_transform.h"

namespace h4::cam {

/// A refined board corner the pose was fitted to, as it travels with the pose
/// (common/formats/README.md#board-corners-csv; board_corners_t on the bus).
struct MeasuredCorner {
  int tag_id = -1;  ///< AprilTag id, -1 for a chessboard corner
  int corner = 0;   ///< BoardModel corner id
  /// px, OpenCV convention, averaged image, less `erosion_px`: where the camera model
  /// projects the board corner (distortion not removed).
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  /// The displacement of the detected corner that the pose fit's erosion explains
  /// (PoseEstimate::corner_erosion_px), px, already removed from `uv`.
  Eigen::Vector2d erosion_px = Eigen::Vector2d::Zero();
  /// Per-axis standard deviation, px: the noise the pose covariance takes for this corner
  /// (PoseEstimate::corner_sigma_px).
  double sigma_px = 0;
};

struct Measurement {
  /// The values of board_pose_t's STATUS_ constants.
  using Status = BoardPoseStatus;
  Status status = Status::kNoBoard;
  std::string message;  ///< why, when not kOk

  RigidTransform X_CT;  ///< board in camera (valid for kOk and kMoved)
  /// 6x6 covariance, order of messages/README.md: (p_CT in C, right rotation vector in T).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double sigma_t = 0;  ///< per-axis position sigma from the fit, m
  double sigma_r = 0;  ///< per-axis rotation sigma from the fit, rad
  int corners_used = 0;
  /// The refined corners the pose was fitted to (kOk and kMoved), in the detector's order.
  std::vector<MeasuredCorner> corners;
  double rms_px = 0;           ///< reprojection RMS of the fit
  double erosion_px = 0;       ///< fitted erosion of the tags (pose_estimator.h), px
  double frame_spread_px = 0;  ///< max per-corner spread between the group's frames
  int frames_averaged = 0;
  int64_t utime = 0;   ///< time of the group's first frame
  std::string origin;  ///< file name of the group's first frame (file sources)

  bool ok() const { return status == Status::kOk; }
};

}  // namespace h4::cam

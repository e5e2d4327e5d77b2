// What a technician needs to know about one camera frame while aiming, focusing and
// collecting intrinsics images (`h4cam capture` / `h4cam preview`): the board's detection
// (tags and corners found, reprojection RMS of a pose fit), a focus figure, the exposure
// (mean level, saturated fraction) and how much of the image the board covers; and the
// frame with the detection drawn over it. Pure: images in, figures and images out. Also the
// check, shared with `h4cam measure`, that a frame has the camera file's size.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "common/camera/camera_model.h"
#include "firmware/detection/board_detector.h"
#include "firmware/frames/frame_source.h"

namespace h4::cam {

struct FrameFigures {
  BoardDetection::Status status = BoardDetection::Status::kNoBoard;
  bool chessboard = false;  ///< the board is a chessboard: corners only, no tags
  int tags = 0;             ///< AprilTag grid: tags found (0 on a chessboard)
  int tags_total = 0;       ///< AprilTag grid: tags on the board
  int corners = 0;          ///< board corners found
  int corners_total = 0;    ///< corners on the board
  /// RMS reprojection error of the pose fit through the camera file's intrinsics, px;
  /// unset when the fit was not possible (too few corners).
  std::optional<double> rms_px;
  /// Variance of the Laplacian of the grey levels over the board's bounding box (the whole
  /// image when no board was found), grey levels^2: grows as the board comes into focus;
  /// compare frames of one scene, not scenes.
  double sharpness = 0;
  double mean_level = 0;          ///< mean grey level of the frame, 0..255
  double saturated_fraction = 0;  ///< fraction of pixels at 255, 0..1
  /// Area of the convex hull of the corners found over the image area, 0..1.
  double coverage = 0;
};

/// Detects the board in `image` (CV_8UC1) and measures the figures above.
FrameFigures CheckFrame(const cv::Mat& image, const BoardDetector& detector,
                        const CameraModel& camera, BoardDetection* detection = nullptr);

/// One line: "board ok, 36/36 tags, 144/144 corners, rms 0.018 px, sharpness 357,
/// mean level 140.5, saturated 0.00 %, coverage 15.7 %" ("board partial, ...",
/// "no board, ..."); on a chessboard "board ok, chessboard: 54/54 corners, rms ...".
std::string FormatFrameFigures(const FrameFigures& figures);

/// The frame in colour with the corners found (green crosses), the hull of the board
/// (yellow), each tag expected wholly in the image but left out (red outline where it was
/// predicted, with its id and why: BoardDetection::missed) and the figures written at the
/// top.
cv::Mat DrawFrameFigures(const cv::Mat& image, const BoardDetection& detection,
                         const FrameFigures& figures);

/// Throws std::runtime_error "<origin>: image is WxH, the camera file <camera_path> says WxH"
/// unless `frame` has the camera file's image size: figures and poses through intrinsics of
/// another size would be wrong without a sign of it. A frame without an origin is "frame".
void RequireTheCameraFilesSize(const Frame& frame, const CameraIntrinsics& camera,
                               const std::string& camera_path);

}  // namespace h4::cam

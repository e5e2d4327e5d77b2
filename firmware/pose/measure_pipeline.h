// The measuring pipeline shared by the camera service and `h4cam measure`:
// frames -> average (N) -> detect the board -> motion check -> pose (PnP + LM) ->
// Measurement. Feed frames one at a time (AddFrame: cheap, keeps up with 30 fps; the
// work happens when a group completes) or a whole group (MeasureFrames).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/camera/camera_model.h"
#include "common/formats/corners_csv.h"
#include "firmware/averaging/frame_averager.h"
#include "firmware/averaging/motion_check.h"
#include "firmware/detection/board_detector.h"
#include "firmware/pose/measurement.h"
#include "firmware/pose/pose_estimator.h"
#include "firmware/frames/frame_source.h"

namespace h4::cam {

struct PipelineOptions {
  int frames = 10;  ///< frames averaged per measurement
  DetectorOptions detector;
  MotionOptions motion;
  PoseOptions pose;
  bool IsValid(std::string* why) const;
};

/// The measurement's corners as rows of the board-corner CSV
/// (common/formats/README.md#board-corners-csv) for pose `pose_id`; each sigma clamped into
/// kCornerSigmaBounds (a perfect synthetic fit has none to speak of, and the format bounds what a
/// weight may be).
std::vector<h4::CornerObservation> CornerRows(const Measurement& m, int64_t pose_id);

class MeasurePipeline {
 public:
  MeasurePipeline(const BoardSpec& board, const CameraIntrinsics& camera,
                  const PipelineOptions& options = {});

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const PipelineOptions& options() const { return options_; }

  /// Adds a frame to the current group; returns the measurement when the group is
  /// complete (and starts the next group). A frame of the wrong type or size gives a
  /// kCameraError measurement and resets the group.
  std::optional<Measurement> AddFrame(const Frame& frame);
  /// Measures the frames added so far (a short last group), then resets. kNoBoard with a
  /// message when no frame was added.
  Measurement Finish();
  /// Measures one whole group (resets any group in progress first).
  Measurement MeasureFrames(const std::vector<Frame>& frames);
  /// Measures an already averaged CV_32FC1 (or CV_8UC1) image: no motion check.
  Measurement MeasureImage(const cv::Mat& image, int frames_averaged) const;
  /// Drops the group in progress.
  void Reset() { averager_.Reset(); }

 private:
  Measurement MeasureGroup();

  PipelineOptions options_;
  CameraModel camera_;
  BoardDetector detector_;
  FrameAverager averager_;
  std::string error_;
};

}  // namespace h4::cam

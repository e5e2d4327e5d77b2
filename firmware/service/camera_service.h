// The core of `h4cam run`: a state machine that takes capture requests, collects N frames
// from a FrameSource, measures them with the MeasurePipeline (average -> detect -> pose)
// and produces board_pose_t messages, plus the content of the camera_status_t heartbeat.
// No LCM and no threads here: the caller (ServiceNode) feeds requests and calls Step();
// tests drive it the same way.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include <h4msgs/board_corners_t.hpp>
#include <h4msgs/board_pose_t.hpp>
#include <h4msgs/camera_status_t.hpp>
#include <h4msgs/capture_request_t.hpp>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/timing/periodic_schedule.h"
#include "firmware/frames/frame_source.h"
#include "firmware/pose/measure_pipeline.h"

namespace h4::cam {

struct CameraServiceOptions {
  std::string camera_id = "h4cam";  ///< camera name put in the messages
  std::string board_id;             ///< board name put in board_pose_t
  int default_frames = 10;          ///< frames per request whose frame_count is 0
  double free_run_hz = 0;           ///< > 0: a measurement (pose_id -1) at this rate when idle
  double max_spread_px = 0.5;       ///< motion threshold of a group
  double exposure_us = 0;           ///< reported in the status (the source applies it)
  double analogue_gain = 1;         ///< reported in the status
  /// Pull frames while idle too: a streaming camera (libcamera) must be drained so that a
  /// request measures frames taken after it, not stale buffers. Off for sim / files.
  bool drain_when_idle = false;
  size_t max_queued_requests = 64;               ///< requests beyond this while busy are rejected
  std::chrono::milliseconds frame_timeout{200};  ///< wait for one frame in Step()
  /// A capture that receives no frame for this long ends with STATUS_CAMERA_ERROR.
  std::chrono::milliseconds capture_timeout{5000};
};

/// Largest frame_count a request may ask for (more is refused as impossible).
inline constexpr int kMaxFramesPerRequest = 1000;

class CameraService {
 public:
  /// Named by ToString, in this order (camera_service.cpp). The values are camera_status_t's
  /// STATE_ constants, so that Status() sends the state as it is.
  enum class State : int8_t {
    kStarting = h4msgs::camera_status_t::STATE_STARTING,
    kIdle = h4msgs::camera_status_t::STATE_IDLE,
    kCapturing = h4msgs::camera_status_t::STATE_CAPTURING,
    kError = h4msgs::camera_status_t::STATE_ERROR,
    kStopping = h4msgs::camera_status_t::STATE_STOPPING,
  };
  using Clock = std::chrono::steady_clock;

  /// `source` must outlive the service.
  CameraService(CameraServiceOptions options, FrameSource& source, const BoardSpec& board,
                const CameraIntrinsics& camera);

  /// Open, Configure, Start the source; false with state kError and last_error() set.
  bool Start();
  /// Stops and closes the source; state kStopping. Pending requests are dropped (logged).
  void Stop();

  /// Queues a request (answered in arrival order). Refused, counted and logged, when
  /// pose_id < 0, frame_count < 0 or > kMaxFramesPerRequest, or the queue is full.
  bool SubmitRequest(const h4msgs::capture_request_t& request);

  /// One step: starts the next queued (or free-running) capture, and pulls at most one
  /// frame from the source when capturing (or draining). Returns the board pose of a
  /// capture that completed in this step.
  std::optional<h4msgs::board_pose_t> Step(Clock::time_point now = Clock::now());

  /// The corners of the board pose the last Step() returned, once (then empty): only for a
  /// STATUS_OK pose, same utime and pose_id (board_corners_t.lcm).
  std::optional<h4msgs::board_corners_t> TakeCorners();

  /// True when Step() will pull a frame (the caller should not block elsewhere then).
  bool WantsFrames() const;

  /// Heartbeat content at `utime` (us since the epoch).
  h4msgs::camera_status_t Status(int64_t utime) const;
  /// Records an error for the status (the service keeps running).
  void RecordError(const std::string& error);

  State state() const { return state_; }
  const std::string& last_error() const { return last_error_; }
  int64_t frames_total() const { return frames_total_; }
  int64_t measurements_total() const { return measurements_total_; }
  int64_t rejected_requests() const { return rejected_requests_; }
  size_t queued_requests() const { return queue_.size(); }

 private:
  struct Capture {
    int64_t pose_id = -1;
    int frames = 0;
    int received = 0;
    Clock::time_point last_progress;
  };
  void BeginCapture(int64_t pose_id, int frames, Clock::time_point now);
  h4msgs::board_pose_t Finish(const Measurement& m, int64_t pose_id);
  h4msgs::board_pose_t FailCapture(const std::string& why);
  void CountFrame(Clock::time_point now);

  CameraServiceOptions options_;
  FrameSource& source_;
  MeasurePipeline pipeline_;
  State state_ = State::kStarting;
  std::string last_error_;
  std::deque<h4msgs::capture_request_t> queue_;
  std::optional<Capture> capture_;
  std::optional<PeriodicSchedule> free_run_;     // when free_run_hz > 0
  std::deque<Clock::time_point> recent_frames_;  // frame times within the last second
  int64_t frames_total_ = 0;
  int64_t measurements_total_ = 0;
  int64_t rejected_requests_ = 0;
  std::optional<h4msgs::board_corners_t> corners_;  // of the last pose, until taken
};

const char* ToString(CameraService::State state);

}  // namespace h4::cam

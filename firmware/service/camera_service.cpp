// The camera service state machine; see camera_service.h.
#include "firmware/service/camera_service.h"

#include <cmath>
#include <exception>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/text/enum_names.h"
#include "firmware/service/measurement_summary.h"
#include "messages/board_pose_status.h"

namespace h4::cam {
namespace {

// The corners that travel with a STATUS_OK pose (messages/README.md, H4_BOARD_CORNERS;
// common/formats/README.md#board-corners-csv); none when there are more than a message
// holds or a value is not finite.
std::optional<h4msgs::board_corners_t> CornersMessage(const Measurement& m,
                                                      const h4msgs::board_pose_t& pose) {
  if (pose.status != h4msgs::board_pose_t::STATUS_OK) return std::nullopt;
  const std::vector<h4::CornerObservation> rows = CornerRows(m, pose.pose_id);
  if (rows.size() > static_cast<size_t>(h4msgs::board_corners_t::MAX_CORNERS)) {
    spdlog::warn("pose {}: {} corners, more than a board_corners_t holds ({}): not sent",
                 pose.pose_id, rows.size(), h4msgs::board_corners_t::MAX_CORNERS);
    return std::nullopt;
  }
  h4msgs::board_corners_t msg{};
  msg.utime = pose.utime;
  msg.pose_id = pose.pose_id;
  msg.camera_id = pose.camera_id;
  msg.corner_count = static_cast<int32_t>(rows.size());
  for (const h4::CornerObservation& c : rows) {
    if (!std::isfinite(c.u) || !std::isfinite(c.v)) return std::nullopt;
    msg.tag_id.push_back(c.tag_id);
    msg.corner.push_back(c.corner);
    msg.u.push_back(c.u);
    msg.v.push_back(c.v);
    msg.sigma_px.push_back(c.sigma_px.value_or(0.0));
  }
  return msg;
}

PipelineOptions MakePipelineOptions(const CameraServiceOptions& options) {
  PipelineOptions p;
  // The service ends each group itself (Finish() after the request's N frames), so the
  // pipeline's own group size is the largest a request may ask for.
  p.frames = kMaxFramesPerRequest;
  p.motion.max_spread_px = options.max_spread_px;
  return p;
}

}  // namespace

constexpr EnumNames<CameraService::State, CameraService::State::kStopping>
    kCameraServiceStateNames = {"starting", "idle", "capturing", "error", "stopping"};

const char* ToString(CameraService::State state) { return kCameraServiceStateNames.NameOf(state); }

CameraService::CameraService(CameraServiceOptions options, FrameSource& source,
                             const BoardSpec& board, const CameraIntrinsics& camera)
    : options_(std::move(options)),
      source_(source),
      pipeline_(board, camera, MakePipelineOptions(options_)) {
  if (!pipeline_.ok()) RecordError("measuring pipeline: " + pipeline_.error());
  if (options_.free_run_hz > 0) {
    free_run_.emplace(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / options_.free_run_hz)));
  }
}

bool CameraService::Start() {
  state_ = State::kStarting;
  if (!pipeline_.ok()) {
    state_ = State::kError;
    return false;
  }
  if (!source_.Open() || !source_.Configure() || !source_.Start()) {
    RecordError(source_.error().empty() ? source_.Describe() + ": cannot start" : source_.error());
    state_ = State::kError;
    source_.Close();
    return false;
  }
  state_ = State::kIdle;
  spdlog::info("camera service started: {}", source_.Describe());
  return true;
}

void CameraService::Stop() {
  if (capture_ || !queue_.empty()) {
    spdlog::warn("stopping with {} request(s) unanswered", queue_.size() + (capture_ ? 1 : 0));
  }
  capture_.reset();
  queue_.clear();
  source_.Stop();
  source_.Close();
  state_ = State::kStopping;
}

bool CameraService::SubmitRequest(const h4msgs::capture_request_t& request) {
  std::string why;
  if (request.pose_id < 0) {
    why = fmt::format("pose_id {} < 0", request.pose_id);
  } else if (request.frame_count < 0 || request.frame_count > kMaxFramesPerRequest) {
    why = fmt::format("frame_count {} outside 0..{}", request.frame_count, kMaxFramesPerRequest);
  } else if (queue_.size() >= options_.max_queued_requests) {
    why = fmt::format("queue full ({} requests waiting)", queue_.size());
  } else if (state_ == State::kError || state_ == State::kStopping) {
    why = std::string("camera ") + ToString(state_);
  }
  if (!why.empty()) {
    ++rejected_requests_;
    spdlog::warn("capture request for pose {} rejected: {} ({} rejected so far)", request.pose_id,
                 why, rejected_requests_);
    return false;
  }
  queue_.push_back(request);
  return true;
}

bool CameraService::WantsFrames() const {
  if (state_ != State::kIdle && state_ != State::kCapturing) return false;
  return capture_.has_value() || !queue_.empty() || options_.drain_when_idle;
}

void CameraService::BeginCapture(int64_t pose_id, int frames, Clock::time_point now) {
  pipeline_.Reset();
  capture_ = Capture{.pose_id = pose_id, .frames = frames, .received = 0, .last_progress = now};
  state_ = State::kCapturing;
}

std::optional<h4msgs::board_pose_t> CameraService::Step(Clock::time_point now) {
  if (state_ != State::kIdle && state_ != State::kCapturing) return std::nullopt;
  if (!capture_) {
    if (!queue_.empty()) {
      const h4msgs::capture_request_t request = queue_.front();
      queue_.pop_front();
      BeginCapture(request.pose_id,
                   request.frame_count == 0 ? options_.default_frames : request.frame_count, now);
    } else if (free_run_ && free_run_->Due(now)) {
      // A late slot (a long capture) gives one measurement, not a burst to catch up.
      BeginCapture(-1, options_.default_frames, now);
    }
  }
  if (!capture_ && !options_.drain_when_idle) return std::nullopt;

  std::optional<Frame> frame = source_.Next(options_.frame_timeout);
  if (!frame) {
    if (!source_.error().empty()) RecordError(source_.error());
    if (capture_ && source_.finished()) {
      return FailCapture(
          fmt::format("{}: no more frames after {}", source_.Describe(), capture_->received));
    }
    if (capture_ && now - capture_->last_progress > options_.capture_timeout) {
      const auto waited =
          std::chrono::duration_cast<std::chrono::milliseconds>(now - capture_->last_progress);
      return FailCapture(fmt::format("no frame for {} ms{}", waited.count(),
                                     last_error_.empty() ? "" : ": " + last_error_));
    }
    return std::nullopt;
  }
  CountFrame(Clock::now());
  if (!capture_) return std::nullopt;  // draining a streaming camera while idle

  capture_->last_progress = now;
  ++capture_->received;
  std::optional<Measurement> m;
  try {
    m = pipeline_.AddFrame(*frame);
    if (!m && capture_->received >= capture_->frames) m = pipeline_.Finish();
  } catch (const std::exception& e) {
    // One capture request must never end the service (under systemd, a few such requests
    // made the unit give up): an error in the measurement (OpenCV's assertions on a board
    // it cannot detect) answers this request with a camera error, and the next one runs.
    return FailCapture(std::string("measurement failed: ") + e.what());
  }
  if (!m) return std::nullopt;
  if (m->status == Measurement::Status::kCameraError) RecordError(m->message);
  return Finish(*m, capture_->pose_id);
}

h4msgs::board_pose_t CameraService::FailCapture(const std::string& why) {
  RecordError(why);
  Measurement m;
  m.status = Measurement::Status::kCameraError;
  m.message = why;
  m.frames_averaged = capture_ ? capture_->received : 0;
  return Finish(m, capture_ ? capture_->pose_id : -1);
}

h4msgs::board_pose_t CameraService::Finish(const Measurement& m, int64_t pose_id) {
  pipeline_.Reset();
  capture_.reset();
  state_ = State::kIdle;
  h4msgs::board_pose_t msg{};
  msg.utime = m.utime;
  msg.pose_id = pose_id;
  msg.camera_id = options_.camera_id;
  msg.board_id = options_.board_id;
  msg.status = ToWire(m.status);
  msg.frames_averaged = m.frames_averaged;
  msg.corners_used = m.corners_used;
  // Only a pose that exists is sent; the others keep zero pose fields (board_pose_t.lcm).
  const bool has_pose =
      m.status == Measurement::Status::kOk || m.status == Measurement::Status::kMoved;
  const bool finite = m.X_CT.translation().allFinite() && m.X_CT.rotation().allFinite() &&
                      m.covariance.allFinite() && std::isfinite(m.rms_px) &&
                      std::isfinite(m.frame_spread_px);
  if (has_pose && finite) {
    const Eigen::Vector4d q = m.X_CT.quaternion_wxyz();
    for (int i = 0; i < 3; ++i) msg.translation[i] = m.X_CT.translation()[i];
    for (int i = 0; i < 4; ++i) msg.quaternion[i] = q[i];
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) msg.covariance[6 * r + c] = m.covariance(r, c);
    }
    msg.reprojection_rms_px = m.rms_px;
    msg.frame_spread_px = m.frame_spread_px;
  } else {
    msg.quaternion[0] = 1;  // identity rather than an invalid all-zero quaternion
    if (has_pose) msg.status = h4msgs::board_pose_t::STATUS_CAMERA_ERROR;
  }
  corners_ = CornersMessage(m, msg);
  ++measurements_total_;
  spdlog::info("pose {}: {}", pose_id, MeasurementSummary(m));
  return msg;
}

std::optional<h4msgs::board_corners_t> CameraService::TakeCorners() {
  std::optional<h4msgs::board_corners_t> corners;
  corners.swap(corners_);
  return corners;
}

void CameraService::CountFrame(Clock::time_point now) {
  ++frames_total_;
  recent_frames_.push_back(now);
  while (!recent_frames_.empty() && now - recent_frames_.front() > std::chrono::seconds(1)) {
    recent_frames_.pop_front();
  }
}

void CameraService::RecordError(const std::string& error) {
  if (error != last_error_) spdlog::warn("camera: {}", error);
  last_error_ = error;
}

h4msgs::camera_status_t CameraService::Status(int64_t utime) const {
  h4msgs::camera_status_t s{};
  s.utime = utime;
  s.camera_id = options_.camera_id;
  s.state = static_cast<int8_t>(state_);
  const auto now = Clock::now();
  int64_t recent = 0;
  for (const auto& t : recent_frames_) recent += (now - t <= std::chrono::seconds(1)) ? 1 : 0;
  s.frame_rate_hz = static_cast<double>(recent);
  s.exposure_us = options_.exposure_us;
  s.analogue_gain = options_.analogue_gain;
  s.frames_total = frames_total_;
  s.measurements_total = measurements_total_;
  s.last_error = last_error_;
  return s;
}

}  // namespace h4::cam

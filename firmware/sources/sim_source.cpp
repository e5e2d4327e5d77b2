// Synthetic frames; see sim_source.h.
#include "firmware/sources/sim_source.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "common/timing/clock.h"

namespace h4::cam {

SimSource::SimSource(const BoardSpec& board, const CameraIntrinsics& camera,
                     SimSourceOptions options)
    : options_(options), renderer_(board, camera, options.render) {}

void SimSource::SetPose(const std::optional<RigidTransform>& X_CT) {
  // Only stored: the next frame renders it. A moving robot sends a pose per joint state,
  // and a camera that is not capturing would otherwise render every one of them (~50 ms
  // each optimised, ~3 s under the sanitizers).
  std::lock_guard<std::mutex> lock(mutex_);
  X_CT_ = X_CT;
}

namespace {
bool SamePose(const std::optional<RigidTransform>& a, const std::optional<RigidTransform>& b) {
  return a.has_value() == b.has_value() && (!a || a->matrix() == b->matrix());
}
}  // namespace

cv::Mat SimSource::CleanImage() {
  std::optional<RigidTransform> X_CT;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // A robot at rest sends the same pose again and again: render it once.
    if (!clean_.empty() && SamePose(X_CT_, clean_pose_)) return clean_;
    X_CT = X_CT_;
  }
  cv::Mat clean = X_CT ? renderer_.RenderClean(*X_CT) : renderer_.RenderBackground();
  std::lock_guard<std::mutex> lock(mutex_);
  clean_pose_ = X_CT;
  clean_ = clean;
  return clean;
}

std::optional<RigidTransform> SimSource::pose() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return X_CT_;
}

bool SimSource::Open() {
  if (!renderer_.ok()) {
    error_ = "sim: " + renderer_.error();
    return false;
  }
  return true;
}

std::optional<Frame> SimSource::Next(std::chrono::milliseconds timeout) {
  if (!renderer_.ok()) {
    error_ = "sim: " + renderer_.error();
    return std::nullopt;
  }
  const double period_us = options_.frame_rate_hz > 0 ? 1e6 / options_.frame_rate_hz : 0.0;
  int64_t utime = options_.start_utime + static_cast<int64_t>(std::llround(sequence_ * period_us));
  if (options_.real_time) {
    // The sensor's next exposure: one period after the last frame, never before now.
    const int64_t due = last_utime_ ? *last_utime_ + static_cast<int64_t>(period_us) : NowUtime();
    const int64_t wait_us = due - NowUtime();
    if (wait_us > 0) {
      if (std::chrono::microseconds(wait_us) > timeout) {
        std::this_thread::sleep_for(timeout);
        return std::nullopt;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(wait_us));
    }
    utime = std::max(due, NowUtime());
    last_utime_ = utime;
  }
  const cv::Mat clean = CleanImage();
  cv::RNG rng(options_.seed * 1000003ULL + static_cast<uint64_t>(sequence_));
  Frame frame;
  frame.image = renderer_.Expose(clean, rng);
  frame.sequence = sequence_;
  frame.utime = utime;
  ++sequence_;
  return frame;
}

}  // namespace h4::cam

// Synthetic frames; see sim_source.h.
#include "firmware/sources/sim_source.h"

#include <algorithm>
#include <cmath>

namespace h4::cam {

SimSource::SimSource(const BoardSpec& board, const CameraIntrinsics& camera,
                     SimSourceOptions options)
    : options_(options),
      renderer_(board, camera, options.render),
      width_(camera.width),
      height_(camera.height) {
  SetPose(std::nullopt);
}

void SimSource::SetPose(const std::optional<RigidTransform>& X_CT) {
  cv::Mat clean = X_CT ? renderer_.RenderClean(*X_CT)
                       : cv::Mat(std::max(height_, 1), std::max(width_, 1), CV_32F,
                                 cv::Scalar(options_.render.background_level));
  std::lock_guard<std::mutex> lock(mutex_);
  X_CT_ = X_CT;
  clean_ = clean;
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

std::optional<Frame> SimSource::Next(std::chrono::milliseconds /*timeout*/) {
  if (!renderer_.ok()) {
    error_ = "sim: " + renderer_.error();
    return std::nullopt;
  }
  cv::Mat clean;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    clean = clean_;
  }
  cv::RNG rng(options_.seed * 1000003ULL + static_cast<uint64_t>(sequence_));
  Frame frame;
  frame.image = renderer_.Expose(clean, rng);
  frame.sequence = sequence_;
  const double period_us = options_.frame_rate_hz > 0 ? 1e6 / options_.frame_rate_hz : 0.0;
  frame.utime = options_.start_utime + static_cast<int64_t>(std::llround(sequence_ * period_us));
  ++sequence_;
  return frame;
}

}  // namespace h4::cam

// Averages a group of N frames in floating point (CV_32F) before detection: the noise of
// the mean falls as 1/sqrt(N) and keeps sub-grey-level precision that an 8-bit mean
// would round away. The frames are kept (by reference, they own their pixels) for the
// motion check. Adding a frame costs one accumulate, so the path keeps up with 30 fps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "firmware/frames/frame_source.h"

namespace h4::cam {

class FrameAverager {
 public:
  /// `frames`: group size N (>= 1).
  explicit FrameAverager(int frames = 10);

  /// Adds a CV_8UC1 frame. False (error() set, frame ignored) for another type or a size
  /// different from the group's first frame.
  bool Add(const Frame& frame);
  bool complete() const { return count() >= target_; }
  int count() const { return static_cast<int>(frames_.size()); }
  int target() const { return target_; }

  /// Mean of the frames added so far, CV_32FC1 (empty before the first frame).
  cv::Mat Mean() const;
  const std::vector<cv::Mat>& frames() const { return frames_; }
  int64_t first_utime() const { return first_utime_; }
  const std::string& first_origin() const { return first_origin_; }
  const std::string& error() const { return error_; }

  /// Starts a new group.
  void Reset();

 private:
  int target_;
  cv::Mat sum_;  // CV_32FC1: exact for up to 65793 frames of 8-bit values
  std::vector<cv::Mat> frames_;
  int64_t first_utime_ = 0;
  std::string first_origin_;
  std::string error_;
};

}  // namespace h4::cam

// Frame averaging; see frame_averager.h.
#include "firmware/averaging/frame_averager.h"

#include <algorithm>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

namespace h4::cam {

FrameAverager::FrameAverager(int frames) : target_(std::max(frames, 1)) {}

bool FrameAverager::Add(const Frame& frame) {
  if (frame.image.empty() || frame.image.type() != CV_8UC1) {
    error_ = fmt::format("frame {}: expected an 8-bit grey image", frame.sequence);
    return false;
  }
  if (!frames_.empty() && frame.image.size() != frames_.front().size()) {
    error_ =
        fmt::format("frame {}: size {}x{} differs from the group's {}x{}", frame.sequence,
                    frame.image.cols, frame.image.rows, frames_.front().cols, frames_.front().rows);
    return false;
  }
  if (frames_.empty()) {
    sum_ = cv::Mat::zeros(frame.image.size(), CV_32FC1);
    first_utime_ = frame.utime;
    first_origin_ = frame.origin;
  }
  cv::accumulate(frame.image, sum_);
  frames_.push_back(frame.image);
  return true;
}

cv::Mat FrameAverager::Mean() const {
  if (frames_.empty()) return {};
  cv::Mat mean;
  sum_.convertTo(mean, CV_32F, 1.0 / static_cast<double>(frames_.size()));
  return mean;
}

void FrameAverager::Reset() {
  frames_.clear();
  sum_.release();
  first_utime_ = 0;
  first_origin_.clear();
  error_.clear();
}

}  // namespace h4::cam

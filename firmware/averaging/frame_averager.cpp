// Frame averaging; see frame_averager.h.
#include "firmware/averaging/frame_averager.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace h4::cam {

FrameAverager::FrameAverager(int frames) : target_(std::max(frames, 1)) {}

bool FrameAverager::Add(const Frame& frame) {
  if (frame.image.empty() || frame.image.type() != CV_8UC1) {
    error_ = "frame " + std::to_string(frame.sequence) + ": expected an 8-bit grey image";
    return false;
  }
  if (!frames_.empty() && frame.image.size() != frames_.front().size()) {
    error_ = "frame " + std::to_string(frame.sequence) + ": size " +
             std::to_string(frame.image.cols) + "x" + std::to_string(frame.image.rows) +
             " differs from the group's " + std::to_string(frames_.front().cols) + "x" +
             std::to_string(frames_.front().rows);
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

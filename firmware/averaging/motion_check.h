// Did the board move during an averaged group? Each frame's image motion relative to the
// group mean is fitted as a small affine warp by one Lucas-Kanade step,
//   I_k(q) - mean(q) = -grad(mean)(q) . (d_k + A_k (q - q0)),
// over the strongest-gradient pixels around the detected corners, and evaluated at every
// corner: the per-frame corner positions without detecting the board in every frame.
// A rigid board moving by much less than a pixel shows as such a warp; large jumps are
// underestimated by the linearisation but still far above any sensible threshold.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace h4::cam {

struct MotionOptions {
  /// Largest allowed distance of a corner's per-frame position from its mean, px.
  double max_spread_px = 0.1;
  int max_pixels = 20000;      ///< strongest-gradient pixels used (speed)
  double roi_margin_px = 8.0;  ///< pixels this far around the corners' bounding box
};

struct MotionEstimate {
  bool valid = false;    ///< false: fewer than 2 frames or no gradient to measure
  double spread_px = 0;  ///< max over frames and corners of |position - mean position|
  bool moved = false;    ///< spread_px > max_spread_px
};

/// `frames`: the group's CV_8UC1 frames; `mean`: their CV_32FC1 mean; `corners_px`: the
/// corners detected on the mean.
MotionEstimate EstimateFrameSpread(const std::vector<cv::Mat>& frames, const cv::Mat& mean,
                                   const std::vector<Eigen::Vector2d>& corners_px,
                                   const MotionOptions& options = {});

}  // namespace h4::cam

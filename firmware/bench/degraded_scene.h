// What a real camera's processed output does to a linear rendering, for the measuring
// pipeline's tests and benchmarks: an unknown monotone response (gamma encoding, as an
// ISP's YUV output), an illumination gradient across the image, and signal-dependent
// noise (shot + read) before 8-bit quantisation. Input: BoardRenderer::RenderClean output
// (linear light, grey levels 0..255, optical blur already applied). Kept apart from the
// renderer so that tests can degrade its clean images in ways it does not model.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace h4::cam::bench {

struct DegradeOptions {
  /// Response exponent: observed = 255 (gain * clean / 255)^gamma. 1 = linear; 0.45 is
  /// close to sRGB encoding. Concave (< 1) responses erode dark features under blur.
  double gamma = 1.0;
  /// Illumination gain varies linearly across the image from 1 - gradient to 1 + gradient
  /// along `gradient_angle` (rad, 0 = from left to right). 0.2 = +-20 %.
  double gradient = 0.0;
  double gradient_angle = 0.0;
  /// Noise before the response, in linear grey levels: variance read^2 + shot * signal.
  double read_noise = 0.0;
  double shot_noise = 0.0;  ///< grey levels of variance per grey level of signal

  bool IsValid(std::string* why) const {
    const char* problem = !(gamma > 0 && gamma <= 2)              ? "gamma must be in (0, 2]"
                          : !(gradient >= 0 && gradient < 1)      ? "gradient must be in [0, 1)"
                          : !(read_noise >= 0 && shot_noise >= 0) ? "noise must be >= 0"
                                                                  : nullptr;
    if (problem != nullptr && why != nullptr) *why = problem;
    return problem == nullptr;
  }
};

/// One degraded 8-bit frame (CV_8UC1) from a clean CV_32FC1 rendering.
inline cv::Mat DegradedFrame(const cv::Mat& clean, const DegradeOptions& options, cv::RNG& rng) {
  CV_Assert(clean.type() == CV_32FC1);
  cv::Mat frame(clean.size(), CV_8UC1);
  const double cx = 0.5 * (clean.cols - 1), cy = 0.5 * (clean.rows - 1);
  const double dx = std::cos(options.gradient_angle), dy = std::sin(options.gradient_angle);
  // Half extent of the image along the gradient direction: the gain spans +-gradient.
  const double half_extent = std::abs(dx) * cx + std::abs(dy) * cy;
  const bool noisy = options.read_noise > 0 || options.shot_noise > 0;
  for (int v = 0; v < clean.rows; ++v) {
    const float* in = clean.ptr<float>(v);
    uint8_t* out = frame.ptr<uint8_t>(v);
    for (int u = 0; u < clean.cols; ++u) {
      const double along = ((u - cx) * dx + (v - cy) * dy) / std::max(half_extent, 1.0);
      double linear = in[u] * (1.0 + options.gradient * along);
      if (noisy) {
        const double variance =
            options.read_noise * options.read_noise + options.shot_noise * std::max(linear, 0.0);
        linear += rng.gaussian(std::sqrt(variance));
      }
      const double x = std::clamp(linear / 255.0, 0.0, 1.0);
      out[u] = cv::saturate_cast<uint8_t>(255.0 * std::pow(x, options.gamma));
    }
  }
  return frame;
}

/// The CV_32FC1 mean of `frames` degraded frames (what the frame averager computes).
inline cv::Mat DegradedMean(const cv::Mat& clean, const DegradeOptions& options, int frames,
                            uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat sum = cv::Mat::zeros(clean.size(), CV_32F);
  for (int k = 0; k < frames; ++k) {
    cv::Mat frame32;
    DegradedFrame(clean, options, rng).convertTo(frame32, CV_32F);
    sum += frame32;
  }
  return sum / static_cast<double>(std::max(frames, 1));
}

}  // namespace h4::cam::bench

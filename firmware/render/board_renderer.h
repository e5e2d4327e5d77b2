// Synthetic camera images of a calibration board at a known pose X_CT, the ground truth
// for the measuring pipeline's tests and benchmarks. The board's region is rendered on a
// grid finer than the pixels, area-sampled (a jittered grid of sub-pixel rays wherever
// a colour boundary may cross, each ray undistorted and intersected with the board
// plane), blurred (Gaussian optics) and integrated over each pixel; then sensor noise
// (Gaussian) and 8-bit quantisation, reproducible from a seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/render/board_pattern.h"

namespace h4::cam {

struct RenderOptions {
  /// The board's region is rendered this many times finer per axis, blurred there, then
  /// averaged back to pixels (optical blur before pixel integration, as in a camera).
  int supersampling = 4;
  /// Area samples per pixel where a colour boundary crosses it, spread over its
  /// supersampling^2 sub-pixels as jittered strata (unbiased whatever the edge direction).
  int samples_per_pixel = 256;
  double blur_sigma_px = 0.8;      ///< optical blur, Gaussian sigma in px (0 = none)
  double noise_sigma = 2.0;        ///< sensor noise per frame, grey levels (0 = none)
  double black_level = 30.0;       ///< grey level of the printed black, 0..255
  double white_level = 220.0;      ///< grey level of the printed white
  double background_level = 90.0;  ///< grey level off the board
  double margin = -1.0;            ///< white border around the pattern, m (<0: one tag/square)

  bool IsValid(std::string* why) const;
};

class BoardRenderer {
 public:
  BoardRenderer(const BoardSpec& board, const CameraIntrinsics& camera, RenderOptions options);

  /// False when the board or camera cannot be rendered (error() says why).
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const RenderOptions& options() const { return options_; }

  /// Noise-free image (area sampling + blur), CV_32F grey levels.
  cv::Mat RenderClean(const RigidTransform& X_CT) const;
  /// One sensor frame from a clean image: noise from `rng`, rounded, saturated, CV_8UC1.
  cv::Mat Expose(const cv::Mat& clean, cv::RNG& rng) const;
  /// RenderClean + Expose with a generator seeded by `seed`.
  cv::Mat Render(const RigidTransform& X_CT, uint64_t seed) const;

 private:
  RenderOptions options_;
  CameraModel camera_;
  BoardPattern pattern_;
  int width_ = 0, height_ = 0;
  std::vector<Eigen::Vector2d> corner_rays_;  // undistorted normalised coordinates of
                                              // pixel corners, (w+1) x (h+1) row-major
  int strata_ = 1;                            // s: s x s jittered samples per edge pixel
  std::string error_;
};

}  // namespace h4::cam

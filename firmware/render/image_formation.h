// The photometric steps of the board renderer around its geometric core (see
// render_options.h for the order): the illumination field, the defocus disk of the PSF
// and the sensor (shot + read noise, saturation, response curve, 8-bit quantisation).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "firmware/render/render_options.h"

namespace h4::cam {

/// Light falling on the scene seen through pixel (u, v), relative to the image centre's:
/// the linear gradient times the cos^4-shaped vignetting of RenderOptions.
class Illumination {
 public:
  Illumination(const RenderOptions& options, int width, int height);

  /// True when the light is 1 everywhere (no multiplication needed).
  bool uniform() const { return uniform_; }
  double At(double u, double v) const;
  /// Multiplies `image` (CV_32F) by the light; its pixel (c, r) is at
  /// (u0 + (c + 0.5) * scale - 0.5, v0 + (r + 0.5) * scale - 0.5) in the image, so a grid
  /// `1/scale` times finer than the pixels starting at pixel corner (u0 - 0.5, v0 - 0.5)
  /// is lit at its own sample centres.
  void Apply(cv::Mat& image, int u0, int v0, double scale) const;

 private:
  bool uniform_ = true;
  double gradient_ = 0, cx_ = 0, cy_ = 0, dx_ = 1, dy_ = 0, extent_ = 1;
  double vignetting_k_ = 0, inv_corner_r2_ = 0;
};

/// Radius (px) of the defocus disk of a point at `depth` (m) for a lens of focal length
/// `fx_px`; 0 when defocus is off (focus_distance or aperture_diameter 0).
double DefocusRadiusPx(const RenderOptions& options, double fx_px, double depth);

/// The normalised pillbox (uniform disk) of `radius` kernel pixels, area-sampled at its
/// rim (CV_32F, odd size); 1 x 1 identity below half a pixel.
cv::Mat PillboxKernel(double radius);

/// Blurs `fine` (CV_32F) with a disk whose radius varies over the image: `radius_map`
/// (CV_32F, radius in fine pixels) holds it per block of map_scale x map_scale fine
/// pixels. The image is blurred at a few radii spanning the range and each pixel
/// interpolates between the two nearest (bands of depth).
void SpatiallyVaryingPillbox(cv::Mat& fine, const cv::Mat& radius_map, int map_scale);

/// The sensor and the image pipeline after the optics: per frame noise, saturation,
/// response curve and 8-bit quantisation.
class SensorModel {
 public:
  explicit SensorModel(const RenderOptions& options);

  /// One 8-bit frame (CV_8UC1) of the linear signal `linear` (CV_32F, grey levels of
  /// full scale), noise drawn from `rng`.
  cv::Mat Expose(const cv::Mat& linear, cv::RNG& rng) const;

 private:
  cv::Mat AddNoise(const cv::Mat& linear, cv::RNG& rng) const;
  cv::Mat Encode(const cv::Mat& signal) const;

  RenderOptions options_;
  /// thresholds_[k]: the linear signal at which the output code rises from k to k + 1
  /// (the response's inverse at k + 0.5), so quantisation is exact for any curve.
  std::vector<float> thresholds_;
};

}  // namespace h4::cam

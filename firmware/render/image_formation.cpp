// Illumination, defocus and sensor of the board renderer; see image_formation.h.
#include "firmware/render/image_formation.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "common/units.h"

namespace h4::cam {

Illumination::Illumination(const RenderOptions& options, int width, int height)
    : uniform_(options.illumination_gradient == 0 && options.vignetting == 0),
      gradient_(options.illumination_gradient),
      cx_(0.5 * (width - 1)),
      cy_(0.5 * (height - 1)) {
  const double angle = RadiansFromDegrees(options.illumination_gradient_direction_deg);
  dx_ = std::cos(angle);
  dy_ = std::sin(angle);
  // The image spans [-extent/2, extent/2] along the direction: the light goes from
  // 1 - gradient/2 to 1 + gradient/2 across it.
  extent_ = std::max(1.0, std::abs(dx_) * width + std::abs(dy_) * height);
  // 1 / (1 + k r^2)^2 = 1 - vignetting at the corner (r = 1).
  vignetting_k_ = 1.0 / std::sqrt(1.0 - std::clamp(options.vignetting, 0.0, 0.99)) - 1.0;
  inv_corner_r2_ = 1.0 / std::max(1.0, cx_ * cx_ + cy_ * cy_);
}

double Illumination::At(double u, double v) const {
  const double du = u - cx_, dv = v - cy_;
  const double linear = 1.0 + gradient_ * (du * dx_ + dv * dy_) / extent_;
  const double fall_off = 1.0 + vignetting_k_ * (du * du + dv * dv) * inv_corner_r2_;
  return linear / (fall_off * fall_off);
}

void Illumination::Apply(cv::Mat& image, int u0, int v0, double scale) const {
  if (uniform_) return;
  for (int r = 0; r < image.rows; ++r) {
    float* row = image.ptr<float>(r);
    const double v = v0 + (r + 0.5) * scale - 0.5;
    for (int c = 0; c < image.cols; ++c) {
      row[c] = static_cast<float>(row[c] * At(u0 + (c + 0.5) * scale - 0.5, v));
    }
  }
}

double DefocusRadiusPx(const RenderOptions& options, double fx_px, double depth) {
  if (options.focus_distance <= 0 || options.aperture_diameter <= 0 || !(depth > 0)) return 0;
  return 0.5 * options.aperture_diameter * fx_px *
         std::abs(1.0 / depth - 1.0 / options.focus_distance);
}

cv::Mat PillboxKernel(double radius) {
  if (!(radius >= 0.5)) return cv::Mat(1, 1, CV_32F, cv::Scalar(1.0f));
  const int half = static_cast<int>(std::ceil(radius + 0.5));
  const int n = 2 * half + 1, sub = 8;  // sub x sub samples per kernel pixel at the rim
  cv::Mat kernel(n, n, CV_32F);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      int inside = 0;
      for (int sy = 0; sy < sub; ++sy) {
        for (int sx = 0; sx < sub; ++sx) {
          const double x = c - half - 0.5 + (sx + 0.5) / sub;
          const double y = r - half - 0.5 + (sy + 0.5) / sub;
          inside += x * x + y * y <= radius * radius ? 1 : 0;
        }
      }
      kernel.at<float>(r, c) = static_cast<float>(inside) / (sub * sub);
    }
  }
  return kernel / cv::sum(kernel)[0];
}

void SpatiallyVaryingPillbox(cv::Mat& fine, const cv::Mat& radius_map, int map_scale) {
  double r_min = 0, r_max = 0;
  cv::minMaxLoc(radius_map, &r_min, &r_max);
  if (r_max < 0.5) return;  // below half a fine pixel: the disk is the identity
  // Bands no more than 0.8 fine pixels (0.2 px at 4x supersampling) of radius apart.
  const int bands = std::clamp(static_cast<int>(std::ceil((r_max - r_min) / 0.8)) + 1, 1, 12);
  if (bands == 1) {
    cv::filter2D(fine, fine, CV_32F, PillboxKernel(0.5 * (r_min + r_max)), cv::Point(-1, -1), 0,
                 cv::BORDER_REPLICATE);
    return;
  }
  const double step = (r_max - r_min) / (bands - 1);
  cv::Mat result = cv::Mat::zeros(fine.size(), CV_32F), blurred;
  for (int k = 0; k < bands; ++k) {
    const double radius = r_min + k * step;
    cv::filter2D(fine, blurred, CV_32F, PillboxKernel(radius), cv::Point(-1, -1), 0,
                 cv::BORDER_REPLICATE);
    for (int r = 0; r < fine.rows; ++r) {
      const float* map_row = radius_map.ptr<float>(std::min(r / map_scale, radius_map.rows - 1));
      const float* in = blurred.ptr<float>(r);
      float* out = result.ptr<float>(r);
      for (int c = 0; c < fine.cols; ++c) {
        const double here = map_row[std::min(c / map_scale, radius_map.cols - 1)];
        const double weight = 1.0 - std::abs(here - radius) / step;  // hat between bands
        if (weight > 0) out[c] += static_cast<float>(weight * in[c]);
      }
    }
  }
  fine = result;
}

SensorModel::SensorModel(const RenderOptions& options) : options_(options) {
  if (options_.response == ResponseCurve::kLinear) return;  // rounding does it
  // Inverse of the response at each half code by bisection (the curves are monotone).
  thresholds_.resize(255);
  for (int k = 0; k < 255; ++k) {
    const double target = (k + 0.5) / 255.0;
    double lo = 0, hi = 1;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (ApplyResponseCurve(options_, mid) < target ? lo : hi) = mid;
    }
    thresholds_[static_cast<size_t>(k)] = static_cast<float>(255.0 * hi);
  }
}

cv::Mat SensorModel::AddNoise(const cv::Mat& linear, cv::RNG& rng) const {
  cv::Mat noisy = linear.clone();
  if (options_.full_well_electrons > 0) {
    // Shot noise (Poisson, variance proportional to the signal, in the Gaussian limit)
    // and read noise from one standard normal draw per pixel.
    cv::Mat normal(linear.size(), CV_32F);
    rng.fill(normal, cv::RNG::NORMAL, 0.0, 1.0);
    const double levels_per_electron = 255.0 / options_.full_well_electrons;
    const double read_variance = options_.noise_sigma * options_.noise_sigma;
    for (int r = 0; r < noisy.rows; ++r) {
      float* out = noisy.ptr<float>(r);
      const float* z = normal.ptr<float>(r);
      for (int c = 0; c < noisy.cols; ++c) {
        const double shot_variance = std::max(0.0f, out[c]) * levels_per_electron;
        out[c] += static_cast<float>(z[c] * std::sqrt(shot_variance + read_variance));
      }
    }
  } else if (options_.noise_sigma > 0) {
    cv::Mat noise(linear.size(), CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    noisy += noise;
  }
  return noisy;
}

cv::Mat SensorModel::Encode(const cv::Mat& signal) const {
  cv::Mat out;
  if (thresholds_.empty()) {
    signal.convertTo(out, CV_8U);  // rounds to nearest and saturates to [0, 255]
    return out;
  }
  out.create(signal.size(), CV_8U);
  for (int r = 0; r < signal.rows; ++r) {
    const float* in = signal.ptr<float>(r);
    unsigned char* code = out.ptr<unsigned char>(r);
    for (int c = 0; c < signal.cols; ++c) {
      // Saturation is implicit: below 0 gives code 0, above full scale 255.
      code[c] = static_cast<unsigned char>(
          std::upper_bound(thresholds_.begin(), thresholds_.end(), in[c]) - thresholds_.begin());
    }
  }
  return out;
}

cv::Mat SensorModel::Expose(const cv::Mat& linear, cv::RNG& rng) const {
  return Encode(AddNoise(linear, rng));
}

}  // namespace h4::cam

// Per-frame board motion in an averaged group; see motion_check.h.
#include "firmware/averaging/motion_check.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Cholesky>

namespace h4::cam {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

/// The board's region of the image (corners' bounding box plus a margin, one pixel clear of
/// the border for the central differences), and the coordinates the affine warp is written
/// in: (pixel - centre) / scale, for conditioning.
struct SpreadRegion {
  int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double scale = 1.0;

  Eigen::Vector2d Normalised(double u, double v) const {
    return {(u - centre.x()) / scale, (v - centre.y()) / scale};
  }
};

std::optional<SpreadRegion> RegionAround(const std::vector<Eigen::Vector2d>& corners_px,
                                        const cv::Mat& mean, double margin_px) {
  Eigen::Vector2d lo = corners_px.front(), hi = corners_px.front();
  for (const Eigen::Vector2d& c : corners_px) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  SpreadRegion region;
  region.u0 = std::max(1, static_cast<int>(lo.x() - margin_px));
  region.v0 = std::max(1, static_cast<int>(lo.y() - margin_px));
  region.u1 = std::min(mean.cols - 2, static_cast<int>(hi.x() + margin_px));
  region.v1 = std::min(mean.rows - 2, static_cast<int>(hi.y() + margin_px));
  if (region.u1 <= region.u0 || region.v1 <= region.v0) return std::nullopt;
  region.centre = 0.5 * (lo + hi);
  region.scale = std::max(1.0, 0.5 * (hi - lo).maxCoeff());
  return region;
}

struct GradientPixel {
  int u = 0, v = 0;
  float gx = 0, gy = 0, g2 = 0;
};

/// The mean image's pixels in the region with a gradient above 2 grey levels per pixel,
/// the strongest `max_pixels` of them.
std::vector<GradientPixel> StrongGradientPixels(const cv::Mat& mean, const SpreadRegion& r,
                                                int max_pixels) {
  std::vector<GradientPixel> pixels;
  pixels.reserve(static_cast<size_t>((r.u1 - r.u0 + 1) * (r.v1 - r.v0 + 1)));
  for (int v = r.v0; v <= r.v1; ++v) {
    const float* up = mean.ptr<float>(v - 1);
    const float* row = mean.ptr<float>(v);
    const float* down = mean.ptr<float>(v + 1);
    for (int u = r.u0; u <= r.u1; ++u) {
      const float gx = 0.5f * (row[u + 1] - row[u - 1]);
      const float gy = 0.5f * (down[u] - up[u]);
      const float g2 = gx * gx + gy * gy;
      if (g2 > 4.0f) pixels.push_back({u, v, gx, gy, g2});
    }
  }
  if (static_cast<int>(pixels.size()) > max_pixels) {
    std::nth_element(pixels.begin(), pixels.begin() + max_pixels, pixels.end(),
                     [](const GradientPixel& a, const GradientPixel& b) { return a.g2 > b.g2; });
    pixels.resize(static_cast<size_t>(max_pixels));
  }
  return pixels;
}

/// Each frame's displacement of every corner against the mean: one Gauss-Newton step of an
/// affine warp (Lucas-Kanade on the six parameters u' = u + w0 + w2 x + w3 y, v' = v + w1 +
/// w4 x + w5 y), enough for sub-pixel motion. Empty when the normal equations fail.
std::vector<std::vector<Eigen::Vector2d>> CornerDisplacements(
    const std::vector<cv::Mat>& frames, const cv::Mat& mean, const SpreadRegion& region,
    const std::vector<GradientPixel>& pixels, const std::vector<Eigen::Vector2d>& corners_px) {
  std::vector<Vector6> jacobians(pixels.size());
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t i = 0; i < pixels.size(); ++i) {
    const GradientPixel& p = pixels[i];
    const Eigen::Vector2d xy = region.Normalised(p.u, p.v);
    jacobians[i] << p.gx, p.gy, p.gx * xy.x(), p.gx * xy.y(), p.gy * xy.x(), p.gy * xy.y();
    H.noalias() += jacobians[i] * jacobians[i].transpose();
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(H);
  std::vector<std::vector<Eigen::Vector2d>> displacement(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    Vector6 b = Vector6::Zero();
    for (size_t i = 0; i < pixels.size(); ++i) {
      const GradientPixel& p = pixels[i];
      b += jacobians[i] *
           (frames[k].at<uint8_t>(p.v, p.u) - static_cast<double>(mean.at<float>(p.v, p.u)));
    }
    const Vector6 w = -ldlt.solve(b);
    if (!w.allFinite()) return {};
    for (const Eigen::Vector2d& c : corners_px) {
      const Eigen::Vector2d xy = region.Normalised(c.x(), c.y());
      displacement[k].emplace_back(w[0] + w[2] * xy.x() + w[3] * xy.y(),
                                   w[1] + w[4] * xy.x() + w[5] * xy.y());
    }
  }
  return displacement;
}

/// The largest distance of a corner's displacement in one frame from its mean over frames.
double LargestSpread(const std::vector<std::vector<Eigen::Vector2d>>& displacement,
                     size_t corners) {
  double spread = 0;
  for (size_t c = 0; c < corners; ++c) {
    Eigen::Vector2d average = Eigen::Vector2d::Zero();
    for (const auto& d : displacement) average += d[c];
    average /= static_cast<double>(displacement.size());
    for (const auto& d : displacement) spread = std::max(spread, (d[c] - average).norm());
  }
  return spread;
}

}  // namespace

MotionEstimate EstimateFrameSpread(const std::vector<cv::Mat>& frames, const cv::Mat& mean,
                                   const std::vector<Eigen::Vector2d>& corners_px,
                                   const MotionOptions& options) {
  MotionEstimate estimate;
  if (frames.size() < 2 || corners_px.empty() || mean.type() != CV_32FC1) return estimate;
  const std::optional<SpreadRegion> region = RegionAround(corners_px, mean, options.roi_margin_px);
  if (!region) return estimate;
  const std::vector<GradientPixel> pixels = StrongGradientPixels(mean, *region, options.max_pixels);
  if (pixels.size() < 50) return estimate;
  const auto displacement = CornerDisplacements(frames, mean, *region, pixels, corners_px);
  if (displacement.empty()) return estimate;
  estimate.valid = true;
  estimate.spread_px = LargestSpread(displacement, corners_px.size());
  estimate.moved = estimate.spread_px > options.max_spread_px;
  return estimate;
}

}  // namespace h4::cam

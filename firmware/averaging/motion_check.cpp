// Per-frame board motion in an averaged group; see motion_check.h.
#include "firmware/averaging/motion_check.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace h4::cam {

MotionEstimate EstimateFrameSpread(const std::vector<cv::Mat>& frames, const cv::Mat& mean,
                                   const std::vector<Eigen::Vector2d>& corners_px,
                                   const MotionOptions& options) {
  MotionEstimate estimate;
  if (frames.size() < 2 || corners_px.empty() || mean.type() != CV_32FC1) return estimate;
  Eigen::Vector2d lo = corners_px.front(), hi = corners_px.front();
  for (const Eigen::Vector2d& c : corners_px) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const int u0 = std::max(1, static_cast<int>(lo.x() - options.roi_margin_px));
  const int v0 = std::max(1, static_cast<int>(lo.y() - options.roi_margin_px));
  const int u1 = std::min(mean.cols - 2, static_cast<int>(hi.x() + options.roi_margin_px));
  const int v1 = std::min(mean.rows - 2, static_cast<int>(hi.y() + options.roi_margin_px));
  if (u1 <= u0 || v1 <= v0) return estimate;
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const double scale = std::max(1.0, 0.5 * (hi - lo).maxCoeff());  // conditioning

  struct Pixel {
    int u, v;
    float gx, gy, g2;
  };
  std::vector<Pixel> pixels;
  pixels.reserve(static_cast<size_t>((u1 - u0 + 1) * (v1 - v0 + 1)));
  for (int v = v0; v <= v1; ++v) {
    const float* up = mean.ptr<float>(v - 1);
    const float* row = mean.ptr<float>(v);
    const float* down = mean.ptr<float>(v + 1);
    for (int u = u0; u <= u1; ++u) {
      const float gx = 0.5f * (row[u + 1] - row[u - 1]);
      const float gy = 0.5f * (down[u] - up[u]);
      const float g2 = gx * gx + gy * gy;
      if (g2 > 4.0f) pixels.push_back({u, v, gx, gy, g2});  // > 2 grey levels per px
    }
  }
  if (pixels.size() < 50) return estimate;
  if (static_cast<int>(pixels.size()) > options.max_pixels) {
    std::nth_element(pixels.begin(), pixels.begin() + options.max_pixels, pixels.end(),
                     [](const Pixel& a, const Pixel& b) { return a.g2 > b.g2; });
    pixels.resize(static_cast<size_t>(options.max_pixels));
  }

  using Vector6 = Eigen::Matrix<double, 6, 1>;
  std::vector<Vector6> jacobians(pixels.size());
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Pixel& p = pixels[i];
    const double x = (p.u - centre.x()) / scale, y = (p.v - centre.y()) / scale;
    jacobians[i] << p.gx, p.gy, p.gx * x, p.gx * y, p.gy * x, p.gy * y;
    H.noalias() += jacobians[i] * jacobians[i].transpose();
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(H);

  // Per frame: warp parameters, then each corner's displacement.
  std::vector<std::vector<Eigen::Vector2d>> displacement(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    Vector6 b = Vector6::Zero();
    for (size_t i = 0; i < pixels.size(); ++i) {
      const Pixel& p = pixels[i];
      const double r =
          frames[k].at<uint8_t>(p.v, p.u) - static_cast<double>(mean.at<float>(p.v, p.u));
      b += jacobians[i] * r;
    }
    const Vector6 w = -ldlt.solve(b);
    if (!w.allFinite()) return estimate;
    for (const Eigen::Vector2d& c : corners_px) {
      const double x = (c.x() - centre.x()) / scale, y = (c.y() - centre.y()) / scale;
      displacement[k].emplace_back(w[0] + w[2] * x + w[3] * y, w[1] + w[4] * x + w[5] * y);
    }
  }
  double spread = 0;
  for (size_t c = 0; c < corners_px.size(); ++c) {
    Eigen::Vector2d average = Eigen::Vector2d::Zero();
    for (const auto& d : displacement) average += d[c];
    average /= static_cast<double>(frames.size());
    for (const auto& d : displacement) spread = std::max(spread, (d[c] - average).norm());
  }
  estimate.valid = true;
  estimate.spread_px = spread;
  estimate.moved = spread > options.max_spread_px;
  return estimate;
}

}  // namespace h4::cam

// Synthetic board images; see board_renderer.h. A pixel centred at (u, v) covers
// [u - 0.5, u + 0.5] x [v - 0.5, v + 0.5] (OpenCV's convention). The undistorted ray of
// every pixel corner is solved once per camera; inside a pixel the ray is interpolated
// bilinearly (the error is below 1e-4 px for mild distortion) and the board point found
// through the inverse of the plane homography [r1 r2 p_CT].
#include "firmware/render/board_renderer.h"

#include <cmath>

#include <Eigen/LU>
#include <opencv2/imgproc.hpp>

namespace h4::cam {
namespace {

// Jittered stratified sampling: an s x s grid of strata, one sample placed at random in
// each, with a per-pixel deterministic generator. (A fixed lattice aliases: an edge
// parallel to one of its short vectors sees a coarse staircase, a systematic shift of
// several hundredths of a pixel along the whole edge. Jitter turns that into independent,
// zero-mean per-pixel errors that average out along an edge.)
struct SplitMix64 {
  uint64_t state;
  double Uniform() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

}  // namespace

bool RenderOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& message) {
    if (why != nullptr) *why = message;
    return false;
  };
  if (samples_per_pixel < 1) return fail("samples_per_pixel must be >= 1");
  if (!(blur_sigma_px >= 0)) return fail("blur sigma must be >= 0 px");
  if (!(noise_sigma >= 0)) return fail("noise sigma must be >= 0 grey levels");
  return true;
}

BoardRenderer::BoardRenderer(const BoardSpec& board, const CameraIntrinsics& camera,
                             RenderOptions options)
    : options_(options),
      camera_(camera),
      pattern_(board, options.margin),
      width_(camera.width),
      height_(camera.height) {
  if (!options_.IsValid(&error_)) return;
  if (!pattern_.ok()) {
    error_ = pattern_.error();
    return;
  }
  if (!camera_.valid() || width_ <= 0 || height_ <= 0) {
    error_ = "camera intrinsics invalid (size, focal length or distortion count)";
    return;
  }
  corner_rays_.resize(static_cast<size_t>((width_ + 1) * (height_ + 1)));
  for (int j = 0; j <= height_; ++j) {
    for (int i = 0; i <= width_; ++i) {
      Eigen::Vector2d xn;
      camera_.NormalizedFromPixel(Eigen::Vector2d(i - 0.5, j - 0.5), &xn);
      corner_rays_[static_cast<size_t>(j * (width_ + 1) + i)] = xn;
    }
  }
  strata_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(options_.samples_per_pixel))));
}

cv::Mat BoardRenderer::RenderClean(const RigidTransform& X_CT) const {
  cv::Mat image(height_, width_, CV_32F, cv::Scalar(options_.background_level));
  if (!ok()) return image;
  // p_C = [r1 r2 p_CT] (x, y, 1)^T for board points; a ray n hits (x, y) with
  // M^-1 n = (x, y, 1) / depth, depth > 0.
  Eigen::Matrix3d M;
  M.col(0) = X_CT.rotation().col(0);
  M.col(1) = X_CT.rotation().col(1);
  M.col(2) = X_CT.translation();
  Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
  if (!lu.isInvertible()) return image;  // camera in the board plane: sees its edge only
  const Eigen::Matrix3d Minv = lu.inverse();

  const float levels[3] = {static_cast<float>(options_.background_level),
                           static_cast<float>(options_.black_level),
                           static_cast<float>(options_.white_level)};
  auto level = [&](BoardPattern::Colour c) { return levels[static_cast<int>(c) + 1]; };
  auto board_point = [&](const Eigen::Vector2d& xn, Eigen::Vector2d* p) {
    const Eigen::Vector3d h = Minv * Eigen::Vector3d(xn.x(), xn.y(), 1.0);
    if (!(h.z() > 1e-12)) return false;
    *p = h.head<2>() / h.z();
    return true;
  };

  // Board point of every pixel corner (valid = in front of the camera).
  const size_t stride = static_cast<size_t>(width_ + 1);
  std::vector<Eigen::Vector2d> points(corner_rays_.size());
  std::vector<unsigned char> valid(corner_rays_.size());
  for (size_t k = 0; k < corner_rays_.size(); ++k) {
    valid[k] = board_point(corner_rays_[k], &points[k]) ? 1 : 0;
  }

  for (int v = 0; v < height_; ++v) {
    float* row = image.ptr<float>(v);
    for (int u = 0; u < width_; ++u) {
      const size_t k00 = static_cast<size_t>(v) * stride + static_cast<size_t>(u);
      const size_t idx[4] = {k00, k00 + 1, k00 + stride, k00 + stride + 1};
      const bool all_valid = valid[idx[0]] && valid[idx[1]] && valid[idx[2]] && valid[idx[3]];
      if (all_valid) {
        Eigen::Vector2d lo = points[idx[0]], hi = points[idx[0]];
        for (int c = 1; c < 4; ++c) {
          lo = lo.cwiseMin(points[idx[c]]);
          hi = hi.cwiseMax(points[idx[c]]);
        }
        // A pixel's footprint is bent by less than this relative amount (distortion
        // over one pixel); widen the box so a boundary near its side is never missed.
        const Eigen::Vector2d pad = 0.05 * (hi - lo);
        lo -= pad;
        hi += pad;
        if (!pattern_.MayChange(lo.x(), lo.y(), hi.x(), hi.y())) {
          const Eigen::Vector2d mid = 0.5 * (lo + hi);
          row[u] = level(pattern_.At(mid.x(), mid.y()));
          continue;
        }
      }
      // Supersample: bilinear ray inside the pixel, exact plane intersection.
      const Eigen::Vector2d& r00 = corner_rays_[idx[0]];
      const Eigen::Vector2d& r10 = corner_rays_[idx[1]];
      const Eigen::Vector2d& r01 = corner_rays_[idx[2]];
      const Eigen::Vector2d& r11 = corner_rays_[idx[3]];
      SplitMix64 rng{static_cast<uint64_t>(v) * 1000003ULL + static_cast<uint64_t>(u)};
      const double step = 1.0 / strata_;
      double sum = 0;
      for (int sy = 0; sy < strata_; ++sy) {
        for (int sx = 0; sx < strata_; ++sx) {
          const double x = (sx + rng.Uniform()) * step, y = (sy + rng.Uniform()) * step;
          const Eigen::Vector2d top = r00 + x * (r10 - r00);
          const Eigen::Vector2d bottom = r01 + x * (r11 - r01);
          Eigen::Vector2d p;
          const BoardPattern::Colour c = board_point(top + y * (bottom - top), &p)
                                             ? pattern_.At(p.x(), p.y())
                                             : BoardPattern::kOff;
          sum += level(c);
        }
      }
      row[u] = static_cast<float>(sum / (strata_ * strata_));
    }
  }
  if (options_.blur_sigma_px > 0) {
    cv::GaussianBlur(image, image, cv::Size(0, 0), options_.blur_sigma_px,
                     options_.blur_sigma_px, cv::BORDER_REPLICATE);
  }
  return image;
}

cv::Mat BoardRenderer::Expose(const cv::Mat& clean, cv::RNG& rng) const {
  cv::Mat noisy = clean.clone();
  if (options_.noise_sigma > 0) {
    cv::Mat noise(clean.size(), CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    noisy += noise;
  }
  cv::Mat out;
  noisy.convertTo(out, CV_8U);  // rounds to nearest and saturates to [0, 255]
  return out;
}

cv::Mat BoardRenderer::Render(const RigidTransform& X_CT, uint64_t seed) const {
  cv::RNG rng(seed);
  return Expose(RenderClean(X_CT), rng);
}

}  // namespace h4::cam

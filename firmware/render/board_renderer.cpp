// Synthetic board images; see board_renderer.h. A pixel centred at (u, v) covers
// [u - 0.5, u + 0.5] x [v - 0.5, v + 0.5] (OpenCV's convention). The ray of every pixel
// corner is solved once per camera (inverting the lens model, not through any of the
// detector's code); inside a pixel the ray is interpolated
// bilinearly (the error is below 1e-4 px for mild distortion) and the board point found
// through the inverse of the plane homography [r1 r2 p_CT]. Each step with an option at
// its neutral value (no light variation, no defocus, linear response, no shot noise) is
// skipped, so the "clean" preset gives the historical images bit for bit.
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

BoardRenderer::BoardRenderer(const BoardSpec& board, const CameraIntrinsics& camera,
                             RenderOptions options)
    : options_(options),
      camera_(camera),
      illumination_(options, camera.width, camera.height),
      sensor_(options),
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
      corner_rays_[static_cast<size_t>(j * (width_ + 1) + i)] = PixelCornerRay(i, j);
    }
  }
  const int f = Supersampling();
  strata_ = std::max(1, static_cast<int>(std::ceil(
                            std::sqrt(static_cast<double>(options_.samples_per_pixel) / (f * f)))));
}

// The ray of pixel corner (i, j). A radtan lens keeps (xn, yn, 1) exactly, so that its
// images stay the same bit for bit; a fisheye's unit rays reach past 90 degrees (z <= 0),
// which normalised coordinates cannot. No ray (beyond the lens's fold): NaN, which no
// board point accepts.
Eigen::Vector3d BoardRenderer::PixelCornerRay(int i, int j) const {
  const Eigen::Vector2d uv(i - 0.5, j - 0.5);
  Eigen::Vector3d ray = Eigen::Vector3d::Constant(NAN);
  if (camera_.distortion_model() == DistortionModel::kEquidistant) {
    camera_.RayFromPixel(uv, &ray);
    return ray;
  }
  Eigen::Vector2d xn;
  if (camera_.NormalizedFromPixel(uv, &xn)) ray = Eigen::Vector3d(xn.x(), xn.y(), 1.0);
  return ray;
}

// The printed board's image plus the reach of the PSF (Gaussian and defocus disk).
// Outside it the image is the lit background, which blur leaves unchanged (the light
// varies slowly). The whole image when part of the board is behind the camera.
BoardRenderer::Region BoardRenderer::BoardRegion(const RigidTransform& X_CT) const {
  const Eigen::Vector2d lo = pattern_.extent_min(), hi = pattern_.extent_max();
  Eigen::Vector2d pmin(1e18, 1e18), pmax(-1e18, -1e18);
  double defocus_px = 0;
  const int steps = 64;  // along each side: distortion bends the sides
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Eigen::Vector2d side[4] = {{lo.x() + t * (hi.x() - lo.x()), lo.y()},
                                     {lo.x() + t * (hi.x() - lo.x()), hi.y()},
                                     {lo.x(), lo.y() + t * (hi.y() - lo.y())},
                                     {hi.x(), lo.y() + t * (hi.y() - lo.y())}};
    for (const Eigen::Vector2d& q : side) {
      const Eigen::Vector3d p_CQ = X_CT * Eigen::Vector3d(q.x(), q.y(), 0.0);
      Eigen::Vector2d uv;
      if (!camera_.ProjectRay(p_CQ, &uv) || !uv.allFinite()) return {0, 0, width_, height_};
      pmin = pmin.cwiseMin(uv);
      pmax = pmax.cwiseMax(uv);
      defocus_px = std::max(
          defocus_px, DefocusRadiusPx(options_, camera_.intrinsics().K(0, 0), FocusDistance(p_CQ)));
    }
  }
  const double reach =
      std::ceil(4.0 * (options_.blur_sigma_px + options_.pixel_blur_sigma_px) + defocus_px) + 2;
  // Clamped before the conversion to int: a board reaching toward 90 degrees off-axis
  // through a radtan lens images its far edge millions of pixels away (converting such a
  // value is undefined, and made the region empty).
  const auto in = [](double v, int size) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(size)));
  };
  return {in(std::floor(pmin.x() - reach), width_), in(std::floor(pmin.y() - reach), height_),
          in(std::ceil(pmax.x() + reach + 1), width_),
          in(std::ceil(pmax.y() + reach + 1), height_)};
}

// The distance a lens focuses on for the board point p_CQ: its depth z for a radtan lens,
// its range |p_CQ| for a fisheye, whose surface of focus is closer to a sphere than a
// plane (and whose z-depth falls to zero at 90 degrees off-axis, which would blur a ring
// of the image into disks of unbounded size).
double BoardRenderer::FocusDistance(const Eigen::Vector3d& p_CQ) const {
  if (camera_.distortion_model() == DistortionModel::kEquidistant) return p_CQ.norm();
  return p_CQ.z();
}

// Defocus disk radius (px) per pixel of the region, from the distance at which the pixel
// centre's ray n meets the board plane (M^-1 n = (x, y, 1) / t with the point at t n).
cv::Mat BoardRenderer::DefocusRadiusMap(const Eigen::Matrix3d& Minv, const Region& region) const {
  cv::Mat radius(region.v1 - region.v0, region.u1 - region.u0, CV_32F);
  const size_t stride = static_cast<size_t>(width_ + 1);
  for (int r = 0; r < radius.rows; ++r) {
    for (int c = 0; c < radius.cols; ++c) {
      const size_t k =
          static_cast<size_t>(region.v0 + r) * stride + static_cast<size_t>(region.u0 + c);
      const Eigen::Vector3d ray = 0.25 * (corner_rays_[k] + corner_rays_[k + 1] +
                                          corner_rays_[k + stride] + corner_rays_[k + stride + 1]);
      const double inverse_t = (Minv * ray).z();
      radius.at<float>(r, c) =
          inverse_t > 1e-12
              ? static_cast<float>(DefocusRadiusPx(options_, camera_.intrinsics().K(0, 0),
                                                   FocusDistance(ray / inverse_t)))
              : 0.0f;
    }
  }
  return radius;
}

namespace {

// The board point (x, y) a ray n meets: M^-1 n = (x, y, 1) / t for the point t n, with
// M = [r1 r2 p_CT]; false when the plane is behind the camera along the ray (t <= 0).
bool BoardPointOnRay(const Eigen::Matrix3d& Minv, const Eigen::Vector3d& ray, Eigen::Vector2d* p) {
  const Eigen::Vector3d h = Minv * ray;
  if (!(h.z() > 1e-12)) return false;
  *p = h.head<2>() / h.z();
  return true;
}

}  // namespace

cv::Mat BoardRenderer::RenderClean(const RigidTransform& X_CT) const {
  cv::Mat image = RenderBackground();
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

  const Region region = BoardRegion(X_CT);
  if (region.u1 <= region.u0 || region.v1 <= region.v0) return image;
  // Render the region f times finer (area-sampled), light and blur it there, then average
  // f x f blocks: optical blur acts on the continuous image before the pixels integrate it,
  // as in a camera. (Blurring the pixel values instead gives a visibly different edge
  // profile for blur sigmas below a pixel.)
  cv::Mat fine = RenderFineRegion(Minv, region);
  ApplyOptics(Minv, region, fine);
  cv::Mat coarse;
  const cv::Rect rect(region.u0, region.v0, region.u1 - region.u0, region.v1 - region.v0);
  cv::resize(fine, coarse, rect.size(), 0, 0, cv::INTER_AREA);
  if (options_.pixel_blur_sigma_px > 0) {
    // The region's border is the uniform background (BoardRegion's reach), which the
    // blur leaves as it is.
    cv::GaussianBlur(coarse, coarse, cv::Size(), options_.pixel_blur_sigma_px,
                     options_.pixel_blur_sigma_px, cv::BORDER_REPLICATE);
  }
  coarse.copyTo(image(rect));
  return image;
}

float BoardRenderer::Level(BoardPattern::Colour colour) const {
  switch (colour) {
    case BoardPattern::kBlack:
      return static_cast<float>(options_.black_level);
    case BoardPattern::kWhite:
      return static_cast<float>(options_.white_level);
    default:
      return static_cast<float>(options_.background_level);
  }
}

// Ray of the fine grid corner (I, J) of the region: bilinear in the pixel-corner rays (z as
// a sum of differences, exactly 1 when the four are a radtan lens's (xn, yn, 1)).
Eigen::Vector3d BoardRenderer::FineRay(const Region& region, int I, int J) const {
  const int f = Supersampling();
  const size_t stride = static_cast<size_t>(width_ + 1);
  const int ci = region.u0 + I / f, cj = region.v0 + J / f;
  const double a = static_cast<double>(I % f) / f, b = static_cast<double>(J % f) / f;
  const size_t k = static_cast<size_t>(cj) * stride + static_cast<size_t>(ci);
  const Eigen::Vector3d& r00 = corner_rays_[k];
  if (a == 0 && b == 0) return r00;
  const Eigen::Vector3d& r10 = corner_rays_[a > 0 ? k + 1 : k];
  const Eigen::Vector3d& r01 = corner_rays_[b > 0 ? k + stride : k];
  const Eigen::Vector3d& r11 = corner_rays_[(a > 0 ? k + 1 : k) + (b > 0 ? stride : 0)];
  const Eigen::Vector2d xy((1 - b) * ((1 - a) * r00.head<2>() + a * r10.head<2>()) +
                           b * ((1 - a) * r01.head<2>() + a * r11.head<2>()));
  const double z_top = r00.z() + a * (r10.z() - r00.z());
  const double z_bottom = r01.z() + a * (r11.z() - r01.z());
  return Eigen::Vector3d(xy.x(), xy.y(), z_top + b * (z_bottom - z_top));
}

// The rays of one row of fine grid corners and the board points they meet.
struct BoardRenderer::FineCornerRow {
  std::vector<Eigen::Vector3d> rays;
  std::vector<Eigen::Vector2d> points;
  std::vector<unsigned char> valid;  ///< the ray meets the board plane in front of the camera
};

void BoardRenderer::FillFineCornerRow(const Eigen::Matrix3d& Minv, const Region& region, int J,
                                      FineCornerRow* row) const {
  const size_t corners = static_cast<size_t>((region.u1 - region.u0) * Supersampling() + 1);
  row->rays.resize(corners);
  row->points.resize(corners);
  row->valid.resize(corners);
  for (size_t i = 0; i < corners; ++i) {
    row->rays[i] = FineRay(region, static_cast<int>(i), J);
    row->valid[i] = BoardPointOnRay(Minv, row->rays[i], &row->points[i]) ? 1 : 0;
  }
}

// The printed pattern over the region, f times finer than the pixels: a fine pixel whose
// four corners fall inside one square takes its level; one that may straddle an edge is
// area-sampled.
cv::Mat BoardRenderer::RenderFineRegion(const Eigen::Matrix3d& Minv, const Region& region) const {
  const int f = Supersampling();
  const int wf = (region.u1 - region.u0) * f, hf = (region.v1 - region.v0) * f;
  cv::Mat fine(hf, wf, CV_32F);
  FineCornerRow rows[2];
  FillFineCornerRow(Minv, region, 0, &rows[0]);
  for (int J = 0; J < hf; ++J) {
    const FineCornerRow& top = rows[J % 2];
    FineCornerRow& bottom = rows[1 - J % 2];
    FillFineCornerRow(Minv, region, J + 1, &bottom);
    float* out = fine.ptr<float>(J);
    for (int I = 0; I < wf; ++I) {
      const size_t i = static_cast<size_t>(I);
      if (top.valid[i] && top.valid[i + 1] && bottom.valid[i] && bottom.valid[i + 1]) {
        const Eigen::Vector2d* p[4] = {&top.points[i], &top.points[i + 1], &bottom.points[i],
                                       &bottom.points[i + 1]};
        Eigen::Vector2d lo = *p[0], hi = *p[0];
        for (int c = 1; c < 4; ++c) {
          lo = lo.cwiseMin(*p[c]);
          hi = hi.cwiseMax(*p[c]);
        }
        if (!pattern_.MayChange(lo.x(), lo.y(), hi.x(), hi.y())) {
          const Eigen::Vector2d mid = 0.5 * (lo + hi);
          out[I] = Level(pattern_.At(mid.x(), mid.y()));
          continue;
        }
      }
      out[I] = AreaSample(Minv, top.rays[i], top.rays[i + 1], bottom.rays[i], bottom.rays[i + 1],
                          static_cast<uint64_t>(J) * 1000003ULL + static_cast<uint64_t>(I));
    }
  }
  return fine;
}

// Mean level over a fine pixel with corner rays r00, r10 (top) and r01, r11 (bottom):
// jittered stratified samples, the ray bilinear inside the pixel and the plane met exactly.
float BoardRenderer::AreaSample(const Eigen::Matrix3d& Minv, const Eigen::Vector3d& r00,
                                const Eigen::Vector3d& r10, const Eigen::Vector3d& r01,
                                const Eigen::Vector3d& r11, uint64_t seed) const {
  SplitMix64 rng{seed};
  const double step = 1.0 / strata_;
  double sum = 0;
  for (int sy = 0; sy < strata_; ++sy) {
    for (int sx = 0; sx < strata_; ++sx) {
      const double x = (sx + rng.Uniform()) * step, y = (sy + rng.Uniform()) * step;
      const Eigen::Vector3d upper = r00 + x * (r10 - r00);
      const Eigen::Vector3d lower = r01 + x * (r11 - r01);
      Eigen::Vector2d q;
      const BoardPattern::Colour c = BoardPointOnRay(Minv, upper + y * (lower - upper), &q)
                                         ? pattern_.At(q.x(), q.y())
                                         : BoardPattern::kOff;
      sum += Level(c);
    }
  }
  return static_cast<float>(sum / (strata_ * strata_));
}

// Light on the board, then the optics (Gaussian PSF, defocus disk), all on the fine image.
void BoardRenderer::ApplyOptics(const Eigen::Matrix3d& Minv, const Region& region,
                                cv::Mat& fine) const {
  const int f = Supersampling();
  illumination_.Apply(fine, region.u0, region.v0, 1.0 / f);
  if (options_.blur_sigma_px > 0) {
    const double sigma = options_.blur_sigma_px * f;
    cv::GaussianBlur(fine, fine, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  }
  if (options_.focus_distance > 0 && options_.aperture_diameter > 0) {
    SpatiallyVaryingPillbox(fine, DefocusRadiusMap(Minv, region) * f, f);
  }
}

cv::Mat BoardRenderer::RenderBackground() const {
  cv::Mat image(std::max(height_, 1), std::max(width_, 1), CV_32F,
                cv::Scalar(options_.background_level));
  if (ok()) illumination_.Apply(image, 0, 0, 1.0);
  return image;
}

cv::Mat BoardRenderer::Expose(const cv::Mat& clean, cv::RNG& rng) const {
  return sensor_.Expose(clean, rng);
}

cv::Mat BoardRenderer::Render(const RigidTransform& X_CT, uint64_t seed) const {
  cv::RNG rng(seed);
  return Expose(RenderClean(X_CT), rng);
}

}  // namespace h4::cam

// Synthetic camera images of a calibration board at a known pose X_CT, the ground truth
// for the measuring pipeline's tests and benchmarks. The board's region is rendered on a
// grid finer than the pixels, area-sampled (a jittered grid of sub-pixel rays wherever
// a colour boundary may cross, each ray undistorted and intersected with the board
// plane; a fisheye's rays past 90 degrees from the axis included), lit (illumination gradient,
// vignetting), blurred by the optics (Gaussian and a depth-dependent defocus disk) and integrated
// over each pixel; then the sensor (shot and read noise, saturation), the response curve and 8-bit
// quantisation, reproducible from a seed. The steps and their options: render_options.h.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/render/board_pattern.h"
#include "firmware/render/image_formation.h"
#include "firmware/render/render_options.h"

namespace h4::cam {

class BoardRenderer {
 public:
  BoardRenderer(const BoardSpec& board, const CameraIntrinsics& camera, RenderOptions options);

  /// False when the board or camera cannot be rendered (error() says why).
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const RenderOptions& options() const { return options_; }

  /// Noise-free linear signal reaching the sensor (radiance x illumination, blurred,
  /// pixel-integrated), CV_32F grey levels of full scale.
  cv::Mat RenderClean(const RigidTransform& X_CT) const;
  /// The same with no board in view: the lit background.
  cv::Mat RenderBackground() const;
  /// One sensor frame from a clean image: noise from `rng`, saturation, response curve,
  /// 8-bit quantisation, CV_8UC1.
  cv::Mat Expose(const cv::Mat& clean, cv::RNG& rng) const;
  /// RenderClean + Expose with a generator seeded by `seed`.
  cv::Mat Render(const RigidTransform& X_CT, uint64_t seed) const;

 private:
  struct Region {  // pixel rectangle [u0, u1) x [v0, v1)
    int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
  };
  Region BoardRegion(const RigidTransform& X_CT) const;
  double FocusDistance(const Eigen::Vector3d& p_CQ) const;
  cv::Mat DefocusRadiusMap(const Eigen::Matrix3d& Minv, const Region& region) const;
  struct FineCornerRow;
  cv::Mat RenderFineRegion(const Eigen::Matrix3d& Minv, const Region& region) const;
  void FillFineCornerRow(const Eigen::Matrix3d& Minv, const Region& region, int J,
                         FineCornerRow* row) const;
  Eigen::Vector3d FineRay(const Region& region, int I, int J) const;
  float AreaSample(const Eigen::Matrix3d& Minv, const Eigen::Vector3d& r00,
                   const Eigen::Vector3d& r10, const Eigen::Vector3d& r01,
                   const Eigen::Vector3d& r11, uint64_t seed) const;
  Eigen::Vector3d PixelCornerRay(int i, int j) const;
  void ApplyOptics(const Eigen::Matrix3d& Minv, const Region& region, cv::Mat& fine) const;
  float Level(BoardPattern::Colour colour) const;
  int Supersampling() const { return std::max(1, options_.supersampling); }

  RenderOptions options_;
  CameraModel camera_;
  Illumination illumination_;
  SensorModel sensor_;
  BoardPattern pattern_;
  int width_ = 0, height_ = 0;
  // Ray directions in C of the pixel corners, (w+1) x (h+1) row-major: (xn, yn, 1) for a
  // radtan lens, unit vectors for a fisheye (whose rays reach past 90 degrees); NaN where
  // the lens images no ray.
  std::vector<Eigen::Vector3d> corner_rays_;
  int strata_ = 1;  // s: s x s jittered samples per edge pixel
  std::string error_;
};

}  // namespace h4::cam

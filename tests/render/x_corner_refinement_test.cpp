// Tests for firmware/detection/x_corner_refinement: the corners of one Kalibr tag (2-cell
// border, corner squares) rendered face-on with known truth are found from a start 0.7 px
// off, also under a strong blur and a gamma 0.45 response, where an X-corner stays put;
// corners too near the image border or options out of range are refused.
#include "firmware/detection/x_corner_refinement.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "firmware/render/board_renderer.h"

namespace h4::cam {
namespace {

CameraIntrinsics FaceOnCamera() {
  return CameraIntrinsics::Pinhole(200, 160, 1000.0, 1000.0, 100.0, 80.0);
}

AprilGridSpec OneKalibrTag() {
  // Kalibr's layout: 2-cell border, corner squares. 60 px: cells of 6 px, corner squares of
  // 18 px.
  return {.cols = 1, .rows = 1, .tag_size = 0.06, .tag_spacing = 0.3};
}

// The camera's response curve: observed = 255 (clean / 255)^gamma.
cv::Mat WithGamma(const cv::Mat& clean, double gamma) {
  cv::Mat out(clean.size(), CV_32F);
  for (int v = 0; v < clean.rows; ++v) {
    for (int u = 0; u < clean.cols; ++u) {
      out.at<float>(v, u) =
          static_cast<float>(255.0 * std::pow(clean.at<float>(v, u) / 255.0, gamma));
    }
  }
  return out;
}

struct Scene {
  cv::Mat image;
  std::array<Eigen::Vector2d, 4> truth;
};

// The tag face-on at 1 m, its top-left corner at a non-integer pixel.
Scene RenderTag(double blur_sigma_px, double gamma) {
  RenderOptions options;
  options.blur_sigma_px = blur_sigma_px;
  options.noise_sigma = 0;
  const AprilGridSpec spec = OneKalibrTag();
  const CameraIntrinsics camera = FaceOnCamera();
  const BoardRenderer renderer(spec, camera, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error();
  const RigidTransform X_CT(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.0297, -0.0311, 1.0));
  Scene scene;
  scene.image = WithGamma(renderer.RenderClean(X_CT), gamma);
  const BoardModel model(spec);
  const CameraModel projection(camera);
  for (int k = 0; k < 4; ++k) {
    projection.Project(X_CT * model.corners()[static_cast<size_t>(k)],
                       &scene.truth[static_cast<size_t>(k)]);
  }
  return scene;
}

double MaxError(const std::array<Eigen::Vector2d, 4>& a, const std::array<Eigen::Vector2d, 4>& b) {
  double worst = 0;
  for (size_t k = 0; k < 4; ++k) worst = std::max(worst, (a[k] - b[k]).norm());
  return worst;
}

std::array<Eigen::Vector2d, 4> Perturbed(const std::array<Eigen::Vector2d, 4>& corners) {
  std::array<Eigen::Vector2d, 4> out = corners;
  const Eigen::Vector2d shifts[4] = {{0.7, 0.0}, {0.0, -0.7}, {-0.5, 0.5}, {0.5, 0.5}};
  for (size_t k = 0; k < 4; ++k) out[k] += shifts[k];
  return out;
}

constexpr double kXRadius = 0.2;  // 2 border cells of 10 (< tagSpacing 0.3)

TEST(XCornerRefinementTest, FindsTheCornersOfASharpTag) {
  const Scene scene = RenderTag(0.8, 1.0);
  auto corners = Perturbed(scene.truth);
  ASSERT_TRUE(RefineXCorners(scene.image, XCornerOptions{}, kXRadius, &corners));
  // Measured: 0.032 px; 0.025 px with 4096 area samples per pixel instead of 256, so most
  // of it is cornerSubPix's own bias on a sharp (blur 0.8 px) X, not rendering noise.
  EXPECT_LT(MaxError(corners, scene.truth), 0.05);
}

TEST(XCornerRefinementTest, BlurAndGammaDoNotMoveAnXCorner) {
  const Scene scene = RenderTag(2.0, 0.45);
  auto corners = Perturbed(scene.truth);
  ASSERT_TRUE(RefineXCorners(scene.image, XCornerOptions{}, kXRadius, &corners));
  // Measured: 0.013 px (0.007 px with 4096 samples per pixel).
  EXPECT_LT(MaxError(corners, scene.truth), 0.02);
}

TEST(XCornerRefinementTest, HalfWindowFollowsTheTagSizeWithinItsLimits) {
  const XCornerOptions options;
  EXPECT_EQ(XCornerHalfWindow(options, 0.2, 60.0), 9);    // 0.8 x 12 px
  EXPECT_EQ(XCornerHalfWindow(options, 0.2, 10.0), 2);    // floor
  EXPECT_EQ(XCornerHalfWindow(options, 0.2, 400.0), 12);  // ceiling
}

TEST(XCornerRefinementTest, EachCornerIsRefinedOnItsOwn) {
  // One corner that cannot be refined (its start 4 px off, farther than max_shift_px)
  // leaves the other three refined and itself untouched; the all-or-nothing form refuses
  // the tag.
  const Scene scene = RenderTag(0.8, 1.0);
  auto corners = Perturbed(scene.truth);
  corners[2] += Eigen::Vector2d(4.0, 0.0);
  const auto start = corners;
  std::array<bool, 4> refined{};
  EXPECT_EQ(RefineEachXCorner(scene.image, XCornerOptions{}, kXRadius, &corners, &refined), 3);
  EXPECT_TRUE(refined[0] && refined[1] && refined[3]);
  EXPECT_FALSE(refined[2]);
  EXPECT_EQ(corners[2], start[2]);
  for (size_t k : {0u, 1u, 3u}) EXPECT_LT((corners[k] - scene.truth[k]).norm(), 0.05) << k;
  auto all_or_nothing = start;
  EXPECT_FALSE(RefineXCorners(scene.image, XCornerOptions{}, kXRadius, &all_or_nothing));
}

TEST(XCornerRefinementTest, CornerAtTheImageBorderOrBadOptionsAreRefused) {
  const Scene scene = RenderTag(0.8, 1.0);
  std::array<Eigen::Vector2d, 4> corners = scene.truth;
  corners[2] = Eigen::Vector2d(1.0, 1.0);
  const auto before = corners;
  EXPECT_FALSE(RefineXCorners(scene.image, XCornerOptions{}, kXRadius, &corners));
  EXPECT_EQ(MaxError(corners, before), 0.0);
  std::string why;
  XCornerOptions options;
  options.window_fraction = 0;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("window_fraction"), std::string::npos);
  options = XCornerOptions{};
  options.max_half_window_px = 1;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_TRUE(XCornerOptions{}.IsValid(&why));
}

}  // namespace
}  // namespace h4::cam

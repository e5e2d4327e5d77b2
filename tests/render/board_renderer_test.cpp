// Tests for firmware/render/board_renderer: area sampling, reproducibility, geometry (a
// rendered corner lands where the camera model projects it, checked through detection),
// the clean preset's images unchanged, and the image formation seen in rendered boards
// (gradient, defocus, saturation).
#include "firmware/render/board_renderer.h"

#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "firmware/detection/board_detector.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

// A camera without distortion, 1 px per mm at 1 m.
CameraIntrinsics UnitCamera() {
  return CameraIntrinsics::Pinhole(320, 240, 1000.0, 1000.0, 160.0, 120.0);
}

// One 80 mm tag: 10 px cells on UnitCamera at 1 m.
AprilGridSpec OneTagBoard() { return {.cols = 1, .rows = 1, .tag_size = 0.08}; }

// `board` facing UnitCamera at 1 m, its tag's left edge (x = 0 in T) at u = 100.0 (a pixel
// centre) and its top edge at v = `top_v`, rendered without blur or noise.
void RenderFacingCamera(const AprilGridSpec& board, RenderOptions options, double top_v,
                        cv::Mat* image) {
  options.blur_sigma_px = 0;
  options.noise_sigma = 0;
  const BoardRenderer renderer(board, UnitCamera(), options);
  ASSERT_TRUE(renderer.ok()) << renderer.error();
  const CameraIntrinsics camera = UnitCamera();
  const double x = (100.0 - camera.K(0, 2)) / camera.K(0, 0);
  const double y = (top_v - camera.K(1, 2)) / camera.K(1, 1);
  *image = renderer.RenderClean(RigidTransform(Eigen::Matrix3d::Identity(), {x, y, 1.0}));
}

TEST(BoardRendererTest, PixelHalfCoveredByAnEdgeIsMidGrey) {
  const RenderOptions options;
  cv::Mat image;
  ASSERT_NO_FATAL_FAILURE(RenderFacingCamera(OneTagBoard(), options, 80.25, &image));
  const float mid = static_cast<float>(0.5 * (options.black_level + options.white_level));
  EXPECT_NEAR(image.at<float>(120, 100), mid, 0.5);
  EXPECT_NEAR(image.at<float>(120, 99), options.white_level, 1e-3);
  EXPECT_NEAR(image.at<float>(120, 101), options.black_level, 1e-3);
  // Pixel row 80 spans v in [79.5, 80.5]: three quarters white (above the tag), a
  // quarter black.
  const double expected = 0.75 * options.white_level + 0.25 * options.black_level;
  EXPECT_NEAR(image.at<float>(80, 130), expected, 0.5);
}

TEST(BoardRendererTest, PixelBlurActsOnThePixelValuesAfterIntegration) {
  // Without optical blur the row across the tag's left edge is white, mid grey (the pixel the
  // edge halves), black; the pixel blur then convolves those pixel values with a sampled
  // Gaussian, as an image pipeline's filter does (not the light before the pixels integrate it).
  RenderOptions options;
  cv::Mat sharp, blurred;
  ASSERT_NO_FATAL_FAILURE(RenderFacingCamera(OneTagBoard(), options, 80.25, &sharp));
  options.pixel_blur_sigma_px = 0.7;
  ASSERT_NO_FATAL_FAILURE(RenderFacingCamera(OneTagBoard(), options, 80.25, &blurred));
  const cv::Mat kernel = cv::getGaussianKernel(7, 0.7, CV_64F);
  for (int u = 97; u <= 103; ++u) {
    double expected = 0;
    for (int k = -3; k <= 3; ++k) {
      expected += kernel.at<double>(k + 3) * sharp.at<float>(120, u - k);
    }
    EXPECT_NEAR(blurred.at<float>(120, u), expected, 0.05) << u;
  }
  EXPECT_GT(blurred.at<float>(120, 101) - sharp.at<float>(120, 101), 20.0);
  std::string why;
  options.pixel_blur_sigma_px = 21;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("pixel blur"), std::string::npos) << why;
}

TEST(BoardRendererTest, SameSeedGivesSameFramesAndNoiseHasRequestedSigma) {
  const BoardRenderer renderer(scenes::PaperBoard(), scenes::PaperCamera(), RenderOptions{});
  ASSERT_TRUE(renderer.ok());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.2, 0.3, 0.1);
  const cv::Mat a = renderer.Render(X_CT, 7), b = renderer.Render(X_CT, 7);
  const cv::Mat c = renderer.Render(X_CT, 8);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  cv::Mat diff;
  cv::subtract(a, c, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(diff, mean, stddev);
  // Difference of two independent noises of sigma 2 (plus rounding): sigma ~ 2.8.
  EXPECT_NEAR(stddev[0], 2.0 * std::sqrt(2.0), 0.15);
}

TEST(BoardRendererTest, RenderedCornersLandWhereTheCameraModelProjects) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  RenderOptions options;
  options.noise_sigma = 0;  // geometry only
  const BoardRenderer renderer(board, camera, options);
  const BoardDetector detector(board, camera);
  const CameraModel model(camera);
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.35, 1.0, 0.4, 0.02, -0.01);
  const BoardDetection detection = detector.Detect(renderer.RenderClean(X_CT));
  ASSERT_EQ(detection.corners.size(), 144u);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(model.Project(X_CT * c.p_TQ, &uv));
    mean += (c.uv - uv) / 144.0;
    EXPECT_LT((c.uv - uv).norm(), 0.02) << "corner " << c.id;
  }
  EXPECT_LT(mean.norm(), 0.002);  // no systematic shift between renderer and model
}

// FNV-1a over the bytes of an image: a compact fingerprint of a whole rendering.
uint64_t Fingerprint(const cv::Mat& image) {
  uint64_t hash = 0xcbf29ce484222325ULL;
  for (int r = 0; r < image.rows; ++r) {
    const unsigned char* p = image.ptr<unsigned char>(r);
    for (size_t k = 0; k < image.cols * image.elemSize(); ++k) {
      hash = (hash ^ p[k]) * 0x100000001b3ULL;
    }
  }
  return hash;
}

// The fingerprints of images rendered by the renderer before the image formation grew
// (commit d79b1a7): the default ("clean") options must keep giving them bit for bit, as
// the tests' accuracy figures were measured on them. (Floating-point results of this
// build's compiler and OpenCV on x86-64; another architecture may round differently.)
TEST(BoardRendererTest, CleanPresetReproducesThePreviousImagesExactly) {
  const AprilGridSpec board = scenes::PaperBoard();
  const BoardRenderer renderer(board, scenes::PaperCamera(), RenderOptions::Clean());
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.35, 1.0, 0.4, 0.02, -0.01);
  EXPECT_EQ(Fingerprint(renderer.RenderClean(X_CT)), 0x104023f170d07e6cULL);
  EXPECT_EQ(Fingerprint(renderer.Render(X_CT, 7)), 0x8ca3f54232480b27ULL);

  RenderOptions sharp = RenderOptions::Clean();
  sharp.blur_sigma_px = 0;
  sharp.noise_sigma = 1.5;
  const BoardRenderer sharp_renderer(board, scenes::PaperCamera(), sharp);
  const RigidTransform X_CT2 = scenes::BoardPose(board, 0.6, 0.2, -0.5, 1.2);
  EXPECT_EQ(Fingerprint(sharp_renderer.Render(X_CT2, 3)), 0xdb451df20bbac4afULL);
}

// Light and dark levels on a fronto-parallel board with only a gradient along +u: both
// scale by the light, which changes by the requested fraction per image width.
TEST(BoardRendererTest, GradientScalesBlackAndWhiteLevelsByTheRequestedFraction) {
  AprilGridSpec board = OneTagBoard();        // white margin of 80 px around the tag
  board.layout = AprilGridLayout::kH4Legacy;  // 1-cell border, no corner squares
  RenderOptions options = RenderOptions::Clean();
  options.illumination_gradient = 0.3;
  // Tag's top at v = 80: the white margin spans u 20..260, the tag's black border cells
  // u 100..110 and 170..180 (and its top row, v 80..90).
  cv::Mat image;
  ASSERT_NO_FATAL_FAILURE(RenderFacingCamera(board, options, 80.0, &image));
  const double width = UnitCamera().width, cx = 0.5 * (width - 1);
  auto light = [&](double u) { return 1.0 + 0.3 * (u - cx) / width; };
  const double white_left = image.at<float>(120, 30), white_right = image.at<float>(120, 250);
  EXPECT_NEAR(white_right / white_left, light(250) / light(30), 1e-4);
  EXPECT_NEAR(white_right - white_left, options.white_level * 0.3 * 220 / width, 0.05);
  const double black_left = image.at<float>(85, 104), black_right = image.at<float>(85, 175);
  EXPECT_NEAR(black_right / black_left, light(175) / light(104), 1e-4);
  // Background (off the board, outside the rendered region) is lit too.
  EXPECT_NEAR(image.at<float>(120, 5) / image.at<float>(120, 315), light(5) / light(315), 1e-4);
}

// Largest intensity step between horizontal neighbours within a pixel box of the image.
double SteepestStep(const cv::Mat& image, const cv::Rect& box) {
  double steepest = 0;
  for (int v = box.y; v < box.y + box.height; ++v) {
    for (int u = box.x; u + 1 < box.x + box.width; ++u) {
      steepest = std::max(steepest, static_cast<double>(std::abs(image.at<float>(v, u + 1) -
                                                                 image.at<float>(v, u))));
    }
  }
  return steepest;
}

// The pixel box where the board band y in [y0, y1] (m, in T) appears.
cv::Rect ImageBoxOfBand(const CameraModel& camera, const RigidTransform& X_CT, double x1, double y0,
                        double y1) {
  cv::Rect box;
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (double x : {0.0, x1}) {
    for (double y : {y0, y1}) {
      Eigen::Vector2d uv;
      camera.Project(X_CT * Eigen::Vector3d(x, y, 0), &uv);
      lo = lo.cwiseMin(uv);
      hi = hi.cwiseMax(uv);
    }
  }
  return cv::Rect(static_cast<int>(lo.x()), static_cast<int>(lo.y()),
                  static_cast<int>(hi.x() - lo.x()), static_cast<int>(hi.y() - lo.y()));
}

// A board tilted about its x axis spans 0.50-0.60 m of depth. Focused at its near edge,
// the far part is blurred by a disk of ~2 px: its edges are much less steep. Without
// defocus both parts are equally sharp (the control).
TEST(BoardRendererTest, DefocusBlursTheBoardMoreFarFromTheFocusDistance) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const RigidTransform X_CT = scenes::BoardPose(board, 0.55, 0.5, 0.0, 0.0);
  const double width = BoardModel(board).pattern_max().x();
  const double height = BoardModel(board).pattern_max().y();
  const CameraModel model(camera);
  const cv::Rect near_box = ImageBoxOfBand(model, X_CT, width, 0.0, 0.25 * height);
  const cv::Rect far_box = ImageBoxOfBand(model, X_CT, width, 0.75 * height, height);
  const double near_depth = (X_CT * Eigen::Vector3d(0, 0, 0)).z();
  const double far_depth = (X_CT * Eigen::Vector3d(0, height, 0)).z();
  ASSERT_GT(far_depth - near_depth, 0.08);

  RenderOptions options = RenderOptions::Clean();
  options.blur_sigma_px = 0.4;
  options.noise_sigma = 0;
  const cv::Mat sharp = BoardRenderer(board, camera, options).RenderClean(X_CT);
  options.focus_distance = near_depth;
  options.aperture_diameter = 0.015;
  const cv::Mat defocused = BoardRenderer(board, camera, options).RenderClean(X_CT);
  EXPECT_GT(DefocusRadiusPx(options, camera.K(0, 0), far_depth), 1.5);

  const double sharp_ratio = SteepestStep(sharp, far_box) / SteepestStep(sharp, near_box);
  EXPECT_NEAR(sharp_ratio, 1.0, 0.1);
  // Near edges stay as sharp as without defocus; far ones lose more than a third.
  EXPECT_GT(SteepestStep(defocused, near_box), 0.85 * SteepestStep(sharp, near_box));
  EXPECT_LT(SteepestStep(defocused, far_box), 0.65 * SteepestStep(sharp, far_box));
}

// A white exposed above full scale clips at code 255, noise or not; the black does not.
TEST(BoardRendererTest, OverexposedWhiteSaturatesAt255) {
  RenderOptions options = RenderOptions::Processed();
  options.white_level = 320;
  const BoardRenderer renderer(scenes::PaperBoard(), scenes::PaperCamera(), options);
  ASSERT_TRUE(renderer.ok()) << renderer.error();
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.5, 0.0, 0.0, 0.0);
  const cv::Mat frame = renderer.Render(X_CT, 5);
  Eigen::Vector2d centre_of_first_gap;  // the white gap between the first two tags
  const AprilGridSpec board = scenes::PaperBoard();
  const double gap_x = board.tag_size * (1 + 0.5 * board.tag_spacing);
  CameraModel(scenes::PaperCamera())
      .Project(X_CT * Eigen::Vector3d(gap_x, 0.5 * board.tag_size, 0), &centre_of_first_gap);
  const cv::Rect gap(static_cast<int>(centre_of_first_gap.x()) - 1,
                     static_cast<int>(centre_of_first_gap.y()) - 10, 3, 20);
  double lo = 0, hi = 0;
  cv::minMaxLoc(frame(gap), &lo, &hi);
  EXPECT_EQ(lo, 255.0);
  cv::minMaxLoc(frame, &lo, &hi);
  EXPECT_LT(lo, 100.0);
}

}  // namespace
}  // namespace h4::cam

// Tests for firmware/detection/board_detector on rendered images with known truth:
// corner accuracy of each refinement, partial boards, no board, chessboards, and Kalibr's
// aprilgrid (2-cell borders, corner squares) at the paper's poses, also through a gamma
// response curve.
#include "firmware/detection/board_detector.h"

#include <array>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "firmware/bench/degraded_scene.h"
#include "firmware/pose/pose_estimator.h"
#include "firmware/render/paper_scenes.h"
#include "tests/support/board_specs.h"

namespace h4::cam {
namespace {

// RMS distance (px) of detected corners from their true projections.
double CornerRms(const BoardDetection& detection, const CameraModel& camera,
                 const RigidTransform& X_CT) {
  double sum = 0;
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector2d uv;
    camera.Project(X_CT * c.p_TQ, &uv);
    sum += (c.uv - uv).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(std::max<size_t>(detection.corners.size(), 1)));
}

TEST(BoardDetectorTest, EdgeFitCornersAreWithinAHundredthOfAPixel) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, RenderOptions{});  // noise 2, blur 0.8
  const CameraModel model(camera);
  DetectorOptions edge, subpix, none;
  subpix.refinement = CornerRefinement::kCornerSubPix;
  none.refinement = CornerRefinement::kNone;
  const BoardDetector edge_detector(board, camera, edge);
  const BoardDetector subpix_detector(board, camera, subpix);
  const BoardDetector none_detector(board, camera, none);
  double sum_edge = 0, sum_subpix = 0, sum_none = 0;
  const auto poses = scenes::RandomPoses(3, 21);
  for (size_t i = 0; i < poses.size(); ++i) {
    const cv::Mat mean = scenes::AveragedFrames(renderer, renderer.RenderClean(poses[i]), 10, i);
    const BoardDetection d = edge_detector.Detect(mean);
    ASSERT_EQ(d.status, BoardDetection::Status::kOk);
    EXPECT_EQ(d.corners.size(), 144u);
    sum_edge += std::pow(CornerRms(d, model, poses[i]), 2);
    sum_subpix += std::pow(CornerRms(subpix_detector.Detect(mean), model, poses[i]), 2);
    sum_none += std::pow(CornerRms(none_detector.Detect(mean), model, poses[i]), 2);
  }
  const double rms_edge = std::sqrt(sum_edge / 3), rms_subpix = std::sqrt(sum_subpix / 3),
               rms_none = std::sqrt(sum_none / 3);
  // Measured per scene (10 frames of noise 2 averaged): edge fit 0.004-0.009 px,
  // libapriltag alone ~0.04 px, cornerSubPix ~0.22 px (the blurred L-shaped tag corners
  // pull it inward).
  EXPECT_LT(rms_edge, 0.01);
  EXPECT_LT(rms_edge, 0.5 * rms_none);
  EXPECT_LT(rms_none, rms_subpix);
}

TEST(BoardDetectorTest, ConcaveResponseErodesTagsAlongTheirErosionDirections) {
  // Under a gamma-0.45 response and 1 px blur every tag side moves toward the dark side:
  // each edge-fitted corner is displaced along the erosion direction it reports (pointing
  // into its tag, about sqrt(2) px per px for a square seen nearly face-on), by the same
  // amount on all tags.
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  RenderOptions render;
  render.blur_sigma_px = 1.0;
  const BoardRenderer renderer(board, camera, render);
  const CameraModel model(camera);
  const BoardDetector detector(board, camera);
  const RigidTransform X_CT = scenes::BoardPose(board, 0.5, 0.2, 0.4, 0.3);
  bench::DegradeOptions degrade;
  degrade.gamma = 0.45;
  degrade.read_noise = 1.0;
  const cv::Mat mean = bench::DegradedMean(renderer.RenderClean(X_CT), degrade, 3, 5);
  const BoardDetection d = detector.Detect(mean);
  ASSERT_EQ(d.status, BoardDetection::Status::kOk);
  double sum_along = 0, sum_across2 = 0;
  for (size_t i = 0; i < d.corners.size(); ++i) {
    const CornerObservation& c = d.corners[i];
    const size_t first = i - i % 4;
    Eigen::Vector2d tag_centre = Eigen::Vector2d::Zero();
    for (size_t k = 0; k < 4; ++k) tag_centre += 0.25 * d.corners[first + k].uv;
    EXPECT_GT(c.erosion_px.dot((tag_centre - c.uv).normalized()), 1.2) << c.id;
    EXPECT_LT(c.erosion_px.norm(), 1.7) << c.id;
    Eigen::Vector2d uv_true;
    model.Project(X_CT * c.p_TQ, &uv_true);
    const Eigen::Vector2d direction = c.erosion_px / c.erosion_px.squaredNorm();
    const double along = (c.uv - uv_true).dot(direction);  // px of erosion
    sum_along += along;
    sum_across2 += std::pow((c.uv - uv_true - along * c.erosion_px).norm(), 2);
  }
  const double n = static_cast<double>(d.corners.size());
  // Measured: ~0.2 px of erosion, what is left across it ~0.0x px.
  EXPECT_GT(sum_along / n, 0.1);
  EXPECT_LT(std::sqrt(sum_across2 / n), 0.25 * sum_along / n);
}

// RMS distance (px) of detected corners from their true projections once each tag's mean
// displacement along its corners' erosion directions is taken out (the pose fit estimates
// erosion; what is left moves the pose).
double CornerRmsLessErosion(const BoardDetection& detection, const CameraModel& camera,
                            const RigidTransform& X_CT) {
  double sum = 0;
  for (size_t first = 0; first + 3 < detection.corners.size(); first += 4) {
    std::array<Eigen::Vector2d, 4> error;
    double erosion = 0;
    for (size_t k = 0; k < 4; ++k) {
      const CornerObservation& c = detection.corners[first + k];
      Eigen::Vector2d uv;
      camera.Project(X_CT * c.p_TQ, &uv);
      error[k] = c.uv - uv;
      erosion += 0.25 * error[k].dot(c.erosion_px) / c.erosion_px.squaredNorm();
    }
    for (size_t k = 0; k < 4; ++k) {
      sum += (error[k] - erosion * detection.corners[first + k].erosion_px).squaredNorm();
    }
  }
  return std::sqrt(sum / static_cast<double>(std::max<size_t>(detection.corners.size(), 1)));
}

using CornerError = double (*)(const BoardDetection&, const CameraModel&, const RigidTransform&);

// RMS corner error of the default detector and of one with `other` options, on noise-free
// renders (`render`) of two random poses of the paper's board (`seed`).
std::pair<double, double> DefaultAndOtherRms(const RenderOptions& render,
                                             const DetectorOptions& other, uint64_t seed,
                                             CornerError corner_error) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, render);
  const CameraModel model(camera);
  const BoardDetector detector(board, camera);
  const BoardDetector other_detector(board, camera, other);
  double sum = 0, sum_other = 0;
  const auto poses = scenes::RandomPoses(2, seed);
  for (const RigidTransform& X_CT : poses) {
    const cv::Mat clean = renderer.RenderClean(X_CT);
    const BoardDetection d = detector.Detect(clean);
    const BoardDetection d_other = other_detector.Detect(clean);
    EXPECT_EQ(d.corners.size(), 144u);
    EXPECT_EQ(d_other.corners.size(), 144u);
    sum += std::pow(corner_error(d, model, X_CT), 2);
    sum_other += std::pow(corner_error(d_other, model, X_CT), 2);
  }
  return {std::sqrt(sum / 2), std::sqrt(sum_other / 2)};
}

TEST(BoardDetectorTest, BlurredInnerBorderEdgeDoesNotBiasTheEdgeFit) {
  // Under a 1.4 px blur the white data cells one border cell (~5-7 px) inside
  // each tag reach the dark side of the fitted band, and which cells are white differs per
  // side: kept clear of (the former fit), they shift the sides unequally and the pose
  // rotates. Noise-free linear renders, so what is left is the fit's own bias.
  RenderOptions render;
  render.blur_sigma_px = 1.4;
  DetectorOptions kept_clear;
  kept_clear.edge_fit.model_inner_edge = false;
  const auto [rms, rms_kept_clear] =
      DefaultAndOtherRms(render, kept_clear, 31, CornerRmsLessErosion);
  // Measured: 0.0054 px modelled, 0.0157 px kept clear.
  EXPECT_LT(rms, 0.008);
  EXPECT_LT(rms, 0.5 * rms_kept_clear);
}

TEST(BoardDetectorTest, LightChangingAlongASideDoesNotTiltTheEdgeFit) {
  // A 30 % illumination gradient and 20 % vignetting, linear response, noise-free: each
  // side's levels change along it. Fitted with constant levels, the sides tilt toward
  // their darker ends and the corners move apart from the truth.
  RenderOptions render;
  render.illumination_gradient = 0.3;
  render.illumination_gradient_direction_deg = 30;
  render.vignetting = 0.2;
  DetectorOptions constant_levels;
  constant_levels.edge_fit.fit_shading = false;
  const auto [rms, rms_constant] = DefaultAndOtherRms(render, constant_levels, 37, CornerRms);
  EXPECT_LT(rms, 0.5 * rms_constant) << rms << " px against " << rms_constant << " px";
}

TEST(BoardDetectorTest, PartlyHiddenBoardStillMeasuresWithFewerCorners) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  RenderOptions options;
  const BoardRenderer renderer(board, camera, options);
  const RigidTransform X_CT = scenes::BoardPose(board, 0.55, 0.2, 0.5, 0.0);
  cv::Mat image = scenes::AveragedFrames(renderer, renderer.RenderClean(X_CT), 10, 4);
  // An arm across the left part of the board.
  cv::rectangle(image, cv::Rect(0, 0, 440, 768), cv::Scalar(60), cv::FILLED);
  const BoardDetector detector(board, camera);
  const BoardDetection detection = detector.Detect(image);
  EXPECT_EQ(detection.status, BoardDetection::Status::kOk);
  EXPECT_GE(detection.corners.size(), 40u);
  EXPECT_LT(detection.corners.size(), 144u);
  EXPECT_LT(CornerRms(detection, CameraModel(camera), X_CT), 0.01);
}

TEST(BoardDetectorTest, TooFewCornersIsPartialAndNoTagIsNoBoard) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, RenderOptions{});
  const RigidTransform X_CT = scenes::BoardPose(board, 0.55, 0.0, 0.0, 0.0);
  cv::Mat image = renderer.Render(X_CT, 5);
  // Keep only a window around the top-left tag(s).
  const CameraModel model(camera);
  Eigen::Vector2d tl, br;
  model.Project(X_CT * Eigen::Vector3d(-0.004, -0.004, 0), &tl);
  model.Project(X_CT * Eigen::Vector3d(0.034, 0.034, 0), &br);
  cv::Mat masked(image.size(), CV_8U, cv::Scalar(200));
  const cv::Rect keep(cv::Point(static_cast<int>(tl.x()), static_cast<int>(tl.y())),
                      cv::Point(static_cast<int>(br.x()), static_cast<int>(br.y())));
  image(keep).copyTo(masked(keep));
  const BoardDetector detector(board, camera);
  const BoardDetection partial = detector.Detect(masked);
  EXPECT_EQ(partial.status, BoardDetection::Status::kPartial);
  EXPECT_EQ(partial.corners.size(), 4u);

  const BoardDetection none = detector.Detect(cv::Mat(768, 1024, CV_8U, cv::Scalar(128)));
  EXPECT_EQ(none.status, BoardDetection::Status::kNoBoard);
  EXPECT_TRUE(none.corners.empty());
}

TEST(BoardDetectorTest, ChessboardCornersAreAccurateAndInModelOrder) {
  const CheckerboardSpec board = Chessboard(9, 6, 0.02, 0.02);
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, RenderOptions{});
  ASSERT_TRUE(renderer.ok()) << renderer.error();
  const BoardDetector detector(board, camera);
  const CameraModel model(camera);
  // Rolled by ~180 degrees: the detector must still put corner 0 at the model's corner 0.
  for (double roll : {0.1, 3.0}) {
    const Eigen::Matrix3d R = So3Exp(Eigen::Vector3d(0.2, -0.1, roll));
    const Eigen::Vector3d centre(0.08, 0.05, 0);
    const RigidTransform X_CT(R, Eigen::Vector3d(0.0, 0.0, 0.5) - R * centre);
    const cv::Mat mean = scenes::AveragedFrames(renderer, renderer.RenderClean(X_CT), 10, 9);
    const BoardDetection detection = detector.Detect(mean);
    ASSERT_EQ(detection.status, BoardDetection::Status::kOk) << roll;
    ASSERT_EQ(detection.corners.size(), 54u);
    EXPECT_LT(CornerRms(detection, model, X_CT), 0.05) << roll;
  }
}

// boards/kalibr_aprilgrid_6x6_30mm.yaml: the paper board's tag grid in Kalibr's design.
AprilGridSpec KalibrPaperBoard() {
  AprilGridSpec board;  // Kalibr's layout
  board.cols = 6;
  board.rows = 6;
  board.tag_size = 0.03;
  board.tag_spacing = 0.3;
  return board;
}

// The camera's response curve applied to a clean rendering: 255 (clean / 255)^gamma.
cv::Mat WithGamma(const cv::Mat& clean, double gamma) {
  cv::Mat normalised = clean / 255.0, out;
  cv::pow(normalised, gamma, out);
  return out * 255.0;
}

struct KalibrRun {
  double corner_rms_px = 0;               // over all poses
  double corner_rms_less_erosion_px = 0;  // each tag's erosion taken out (CornerRmsLessErosion)
  size_t edge_fitted = 0;                 // corners from edge fits
  double worst_position_m = 0;            // pose error of the fit against the truth
  double worst_rotation_rad = 0;
  Eigen::Vector2d mean_error_px = Eigen::Vector2d::Zero();  // detected - true
};

// Renders the Kalibr board at `poses`, detects it (every tag must be found) and fits the
// pose; `gamma` 1 is a linear camera.
KalibrRun RunKalibrScenes(const std::vector<RigidTransform>& poses, const RenderOptions& render,
                          double gamma, CornerRefinement refinement) {
  const AprilGridSpec board = KalibrPaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardRenderer renderer(board, camera, render);
  EXPECT_TRUE(renderer.ok()) << renderer.error();
  DetectorOptions options;
  options.refinement = refinement;
  const BoardDetector detector(board, camera, options);
  EXPECT_TRUE(detector.ok()) << detector.error();
  const CameraModel model(camera);
  KalibrRun run;
  double sum = 0, sum_less_erosion = 0;
  size_t count = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const cv::Mat clean = WithGamma(renderer.RenderClean(poses[i]), gamma);
    const BoardDetection d = detector.Detect(scenes::AveragedFrames(renderer, clean, 10, i));
    EXPECT_EQ(d.tags, 36) << "pose " << i << ", tags rejected " << d.tags_rejected;
    EXPECT_EQ(d.corners.size(), 144u) << "pose " << i;
    if (refinement == CornerRefinement::kEdgeFit) {  // X-corners have no erosion direction
      sum_less_erosion += std::pow(CornerRmsLessErosion(d, model, poses[i]), 2) *
                          static_cast<double>(d.corners.size());
    }
    for (const CornerObservation& c : d.corners) {
      if (c.edge_group >= 0) ++run.edge_fitted;
      Eigen::Vector2d uv;
      model.Project(poses[i] * c.p_TQ, &uv);
      sum += (c.uv - uv).squaredNorm();
      run.mean_error_px += c.uv - uv;
      ++count;
    }
    const PoseEstimate pose = EstimatePose(d.corners, model);
    EXPECT_TRUE(pose.ok()) << pose.message;
    const RigidTransform X_error = poses[i].inverse() * pose.X_CT;
    run.worst_position_m = std::max(run.worst_position_m, X_error.translation().norm());
    run.worst_rotation_rad =
        std::max(run.worst_rotation_rad, Eigen::AngleAxisd(X_error.rotation()).angle());
  }
  run.corner_rms_px = std::sqrt(sum / static_cast<double>(std::max<size_t>(count, 1)));
  run.corner_rms_less_erosion_px =
      std::sqrt(sum_less_erosion / static_cast<double>(std::max<size_t>(count, 1)));
  run.mean_error_px /= static_cast<double>(std::max<size_t>(count, 1));
  std::printf(
      "corner RMS %.4f px (%.4f px less erosion), mean error (%.4f, %.4f) px, %zu edge-fitted, "
      "worst pose error %.4f mm, %.4f deg\n",
      run.corner_rms_px, run.corner_rms_less_erosion_px, run.mean_error_px.x(),
      run.mean_error_px.y(), run.edge_fitted, run.worst_position_m * 1e3,
      DegreesFromRadians(run.worst_rotation_rad));
  return run;
}

// RunKalibrScenes at three of the paper's poses (0.45-0.65 m, tilt up to 25 deg), linear camera.
KalibrRun RunKalibrAtThePapersPoses(CornerRefinement refinement) {
  return RunKalibrScenes(scenes::RandomPoses(3, 21), RenderOptions{}, 1.0, refinement);
}

// RunKalibrScenes at two poses through a concave response (gamma 0.45) and a blur of 1 px.
KalibrRun RunKalibrUnderGammaAndBlur(CornerRefinement refinement) {
  RenderOptions render;
  render.blur_sigma_px = 1.0;
  return RunKalibrScenes(scenes::RandomPoses(2, 5), render, 0.45, refinement);
}

// What the X-corners alone give in either scene: corner RMS below `corner_rms_px`, a mean
// error below 0.005 px, and a pose within 0.05 mm and 0.02 deg.
void ExpectXCornersUnbiasedWithPoseWithinBounds(const KalibrRun& run, double corner_rms_px) {
  EXPECT_LT(run.corner_rms_px, corner_rms_px);
  EXPECT_LT(run.mean_error_px.norm(), 0.005);
  EXPECT_LT(run.worst_position_m, 0.05e-3);
  EXPECT_LT(run.worst_rotation_rad, RadiansFromDegrees(0.02));
}

TEST(BoardDetectorTest, KalibrBoardEdgeFitCornersAreWithinAHundredthOfAPixel) {
  // The tag sides of Kalibr's board are fitted between its corner squares, from the
  // X-corners' positions, as precisely as the legacy board's
  // (EdgeFitCornersAreWithinAHundredthOfAPixel, the same scenes).
  const KalibrRun run = RunKalibrAtThePapersPoses(CornerRefinement::kEdgeFit);
  // Measured (render noise 2, blur 0.8, 10 frames averaged): corner RMS 0.0050 px, worst
  // pose error 0.0012 mm and 0.0012 deg (the X-corners alone, next test: 0.024 px, 0.018 mm
  // and 0.010 deg).
  EXPECT_EQ(run.edge_fitted, 3 * 144u);
  EXPECT_LT(run.corner_rms_px, 0.01);
  EXPECT_LT(run.worst_position_m, 0.01e-3);
  EXPECT_LT(run.worst_rotation_rad, RadiansFromDegrees(0.005));
}

TEST(BoardDetectorTest, KalibrBoardIsFoundWholeWithXCornersAtThePapersPoses) {
  // The X-corners alone (what a tag whose sides do not fit keeps).
  const KalibrRun run = RunKalibrAtThePapersPoses(CornerRefinement::kXCorner);
  // Measured (render noise 2, blur 0.8, 10 frames averaged): corner RMS 0.024 px, mean
  // error (-0.0002, -0.0004) px, worst pose error 0.018 mm and 0.010 deg. cornerSubPix
  // keeps a bias of ~0.025 px on a sharp X-corner (x_corner_refinement_test), so this is
  // about 3x the edge fit's (KalibrBoardEdgeFitCornersAreWithinAHundredthOfAPixel).
  EXPECT_EQ(run.edge_fitted, 0u);
  ExpectXCornersUnbiasedWithPoseWithinBounds(run, 0.035);
}

TEST(BoardDetectorTest, KalibrXCornersStayUnbiasedUnderGammaAndBlur) {
  const KalibrRun run = RunKalibrUnderGammaAndBlur(CornerRefinement::kXCorner);
  // Measured: corner RMS 0.021 px, mean error (-0.0012, -0.0001) px, worst pose error
  // 0.008 mm and 0.006 deg: the response curve does not move an X-corner.
  ExpectXCornersUnbiasedWithPoseWithinBounds(run, 0.03);
}

TEST(BoardDetectorTest, KalibrEdgeFitUnderGammaAndBlurErodesTheTagsAndThePoseFitTakesItOut) {
  // A concave response erodes the tags' sides under blur: the edge-fitted corners move
  // along the erosion directions they report (about 0.2 px here), the corner squares and
  // the data cells do not move the sides otherwise, and the pose fit, which estimates the
  // erosion, stays as precise as on a linear camera.
  const KalibrRun run = RunKalibrUnderGammaAndBlur(CornerRefinement::kEdgeFit);
  // Measured: corner RMS 0.50 px, 0.0096 px once each tag's erosion is taken out, worst
  // pose error 0.0053 mm and 0.0010 deg.
  EXPECT_EQ(run.edge_fitted, 2 * 144u);
  EXPECT_GT(run.corner_rms_px, 0.1);
  EXPECT_LT(run.corner_rms_less_erosion_px, 0.015);
  EXPECT_LT(run.worst_position_m, 0.01e-3);
  EXPECT_LT(run.worst_rotation_rad, RadiansFromDegrees(0.005));
}

}  // namespace
}  // namespace h4::cam

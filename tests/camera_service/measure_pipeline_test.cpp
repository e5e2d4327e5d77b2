// Accuracy of the whole measuring pipeline (average 10 frames -> detect -> pose) on
// rendered scenes like the paper's, against the camera's goals: position error RMS
// <= 0.05 mm, rotation error RMS <= 0.01 deg, reported sigma within a factor 2 of the
// actual error. firmware/bench/measure_accuracy runs the same on more scenes.
#include "firmware/pose/measure_pipeline.h"

#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "firmware/bench/degraded_scene.h"
#include "firmware/render/board_renderer.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"
#include "tests/render/paper_scene_helpers.h"

namespace h4::cam {
namespace {

/// The camera's goal for the reported sigma: within a factor 2 of the actual error, in
/// position and in rotation (sums of squares over the same measurements).
void ExpectSigmaHonest(double sig_t2, double err_t2, double sig_r2, double err_r2) {
  const double ratio_t = std::sqrt(sig_t2 / err_t2), ratio_r = std::sqrt(sig_r2 / err_r2);
  EXPECT_GT(ratio_t, 0.5);
  EXPECT_LT(ratio_t, 2.0);
  EXPECT_GT(ratio_r, 0.5);
  EXPECT_LT(ratio_r, 2.0);
}

TEST(MeasurePipelineStudy, PaperScenesMeetAccuracyGoalsAndSigmaIsHonest) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  SimSourceOptions sim;
  sim.seed = 99;
  SimSource source(board, camera, sim);
  ASSERT_TRUE(source.Open()) << source.error();
  MeasurePipeline pipeline(board, camera);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error();
  double err_t2 = 0, err_r2 = 0, sig_t2 = 0, sig_r2 = 0;
  const auto poses = scenes::RandomPoses(6, 2024);
  for (const RigidTransform& X_CT : poses) {
    source.SetPose(X_CT);
    std::optional<Measurement> m;
    while (!m) m = pipeline.AddFrame(*source.Next(std::chrono::milliseconds(0)));
    ASSERT_EQ(m->status, Measurement::Status::kOk) << m->message;
    EXPECT_EQ(m->corners_used, 144);
    const Eigen::Vector3d e_t = m->X_CT.translation() - X_CT.translation();
    const Eigen::Vector3d e_r = So3Log(X_CT.rotation().transpose() * m->X_CT.rotation());
    err_t2 += e_t.squaredNorm() / 3;  // per axis, as sigma_t is
    err_r2 += e_r.squaredNorm() / 3;
    sig_t2 += m->sigma_t * m->sigma_t;
    sig_r2 += m->sigma_r * m->sigma_r;
  }
  const double n = static_cast<double>(poses.size());
  const double rms_t = std::sqrt(3 * err_t2 / n), rms_r = std::sqrt(3 * err_r2 / n);
  EXPECT_LT(rms_t, 0.05e-3);                   // position error RMS (norm), m
  EXPECT_LT(rms_t, 0.01e-3);                   // the erosion fit keeps clean scenes
  EXPECT_LT(rms_r, RadiansFromDegrees(0.01));  // rotation error RMS (angle), rad
  ExpectSigmaHonest(sig_t2, err_t2, sig_r2, err_r2);
}

TEST(MeasurePipelineStudy, UnknownResponseBlurAndGradientKeepThePoseWithinGoals) {
  // Scenes whose response (gamma 0.45-0.8), blur (0.6-1.5 px), +-20 %
  // illumination gradient and shot noise the pipeline is not told about. Without the
  // erosion parameters the position error is ~0.3-0.5 mm here (tags look eroded, the board
  // smaller, hence farther). Three frames averaged to keep the test short.
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  MeasurePipeline pipeline(board, camera);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error();
  // Blur up to 1.5 px: beyond ~1.2 px the rotation error was 0.005-0.009 deg until the
  // edge fit modelled the tag border's inner edge (edge_refinement.h, model_inner_edge).
  const double blur_px[] = {0.6, 1.5, 1.2, 1.0};
  const double gamma[] = {0.45, 0.6, 0.8, 0.45};
  const auto poses = scenes::RandomPoses(4, 77);
  double err_t2 = 0, err_r2 = 0, sig_t2 = 0, sig_r2 = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    RenderOptions render;
    render.blur_sigma_px = blur_px[i];
    const BoardRenderer renderer(board, camera, render);
    bench::DegradeOptions degrade;
    degrade.gamma = gamma[i];
    degrade.gradient = 0.2;
    degrade.gradient_angle = 1.3 * static_cast<double>(i);
    degrade.read_noise = 1.0;
    degrade.shot_noise = 0.03;
    const cv::Mat mean = bench::DegradedMean(renderer.RenderClean(poses[i]), degrade, 3, i);
    const Measurement m = pipeline.MeasureImage(mean, 3);
    ASSERT_EQ(m.status, Measurement::Status::kOk) << m.message;
    EXPECT_GT(m.erosion_px, 0.02) << i;  // concave response: the tags look eroded
    const Eigen::Vector3d e_t = m.X_CT.translation() - poses[i].translation();
    const Eigen::Vector3d e_r = So3Log(poses[i].rotation().transpose() * m.X_CT.rotation());
    err_t2 += e_t.squaredNorm() / 3;
    err_r2 += e_r.squaredNorm() / 3;
    sig_t2 += m.sigma_t * m.sigma_t;
    sig_r2 += m.sigma_r * m.sigma_r;
  }
  const double n = static_cast<double>(poses.size());
  EXPECT_LT(std::sqrt(3 * err_t2 / n), 0.03e-3);
  EXPECT_LT(std::sqrt(3 * err_r2 / n), RadiansFromDegrees(0.005));
  ExpectSigmaHonest(sig_t2, err_t2, sig_r2, err_r2);
}

// Mean displacement of corners toward their tag's centre (px) against the true projections:
// what a uniform erosion of the tags does to them. `detected`: the corners as detected
// (uv + erosion_px), else as exported.
double MeanShiftTowardTagCentre(const Measurement& m, const BoardModel& board,
                                const CameraModel& camera, const RigidTransform& X_CT,
                                bool detected) {
  std::map<int, std::vector<const MeasuredCorner*>> by_tag;
  for (const MeasuredCorner& c : m.corners) by_tag[c.corner / 4].push_back(&c);
  double sum = 0;
  int n = 0;
  for (const auto& [tag, corners] : by_tag) {
    if (corners.size() != 4) continue;
    std::vector<Eigen::Vector2d> truth;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const MeasuredCorner* c : corners) {
      Eigen::Vector2d uv;
      camera.Project(X_CT * *board.Corner(c->corner), &uv);
      truth.push_back(uv);
      centre += 0.25 * uv;
    }
    for (size_t k = 0; k < corners.size(); ++k) {
      const Eigen::Vector2d uv =
          detected ? corners[k]->uv + corners[k]->erosion_px : corners[k]->uv;
      sum += (uv - truth[k]).dot((centre - truth[k]).normalized());
      ++n;
    }
  }
  return n > 0 ? sum / n : NAN;
}

TEST(MeasurePipelineTest, ExportedCornersCarryNoErosion) {
  // A response curve the renderer does not apply (gamma 0.7 on its linear frames) after
  // optical blur and a blur of the pixel values the edge model does not assume, with a
  // gradient and noise: every detected corner moves toward its tag's centre (~0.3 px). The
  // corners h4cam exports (measure --corners-out, board_corners_t) are the detected ones
  // less the erosion the pose fit explains, so a pixel-space fit downstream (the corner
  // path) does not read the shrinkage as a focal length.
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const BoardModel model(board);
  const CameraModel projection(camera);
  MeasurePipeline pipeline(board, camera);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error();
  RenderOptions render;
  render.blur_sigma_px = 1.0;
  render.pixel_blur_sigma_px = 0.8;
  const BoardRenderer renderer(board, camera, render);
  const auto poses = scenes::RandomPoses(2, 41);
  for (size_t i = 0; i < poses.size(); ++i) {
    bench::DegradeOptions degrade;
    degrade.gamma = 0.7;
    degrade.gradient = 0.2;
    degrade.read_noise = 1.0;
    const cv::Mat mean = bench::DegradedMean(renderer.RenderClean(poses[i]), degrade, 3, i);
    const Measurement m = pipeline.MeasureImage(mean, 3);
    ASSERT_EQ(m.status, Measurement::Status::kOk) << m.message;
    EXPECT_GT(MeanShiftTowardTagCentre(m, model, projection, poses[i], true), 0.2) << i;
    EXPECT_LT(std::abs(MeanShiftTowardTagCentre(m, model, projection, poses[i], false)), 0.02) << i;
  }
}

// Issue 41: measured with a camera file as wrong as an ordinary intrinsic calibration (fx
// +0.15 %, fy +0.12 %, cx +0.7 px, cy -0.5 px, k1 +1 %), the pose fit's residuals grow with
// the file's misfit, and the exported corners' sigma_px took all of it (3x the exact file's
// on the same images), although the corners are as good: the corner path, which refines
// the camera, then overstated its error. The misfit is smooth over the board and stays out.
TEST(MeasurePipelineTest, AWrongCameraFilesMisfitStaysOutOfTheCornersSigma) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  CameraIntrinsics typical = camera;
  typical.K(0, 0) *= 1.0015;
  typical.K(1, 1) *= 1.0012;
  typical.K(0, 2) += 0.7;
  typical.K(1, 2) -= 0.5;
  typical.distortion[0] *= 1.01;
  MeasurePipeline exact_pipeline(board, camera), typical_pipeline(board, typical);
  ASSERT_TRUE(exact_pipeline.ok() && typical_pipeline.ok());
  const BoardRenderer renderer(board, camera, RenderOptions{});
  const auto poses = scenes::RandomPoses(2, 43);
  for (size_t i = 0; i < poses.size(); ++i) {
    bench::DegradeOptions degrade;
    degrade.read_noise = 1.0;
    const cv::Mat mean = bench::DegradedMean(renderer.RenderClean(poses[i]), degrade, 10, i);
    const Measurement exact = exact_pipeline.MeasureImage(mean, 10);
    const Measurement wrong = typical_pipeline.MeasureImage(mean, 10);
    ASSERT_TRUE(exact.ok() && wrong.ok()) << exact.message << wrong.message;
    // The scene shows the file wrong: its fit leaves clearly more misfit.
    EXPECT_GT(wrong.rms_px, 1.5 * exact.rms_px) << i;
    auto mean_sigma = [](const Measurement& m) {
      double sum = 0;
      for (const MeasuredCorner& c : m.corners) sum += c.sigma_px / m.corners.size();
      return sum;
    };
    EXPECT_LT(mean_sigma(wrong), 1.3 * mean_sigma(exact))
        << i << ": " << mean_sigma(wrong) << " px against " << mean_sigma(exact) << " px";
  }
}

TEST(MeasurePipelineTest, EmptySceneGivesNoBoard) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  SimSource source(board, camera, SimSourceOptions{});
  ASSERT_TRUE(source.Open());
  MeasurePipeline pipeline(board, camera);
  std::vector<Frame> frames;
  for (int k = 0; k < 3; ++k) frames.push_back(*source.Next(std::chrono::milliseconds(0)));
  const Measurement m = pipeline.MeasureFrames(frames);
  EXPECT_EQ(m.status, Measurement::Status::kNoBoard);
  EXPECT_EQ(m.frames_averaged, 3);
  EXPECT_TRUE(m.X_CT.translation().allFinite());
}

// issue 27 point 17: two boards in view were refused (safe) with "no board corner found"
// although every tag was decoded: each id was seen twice. The message says so.
TEST(MeasurePipelineTest, TwoBoardsInViewSayTheIdsWereSeenTwice) {
  const PaperScene scene;
  const CameraIntrinsics& camera = scene.camera;
  // The same board left and right of the image's centre, each wholly in its half.
  cv::Mat both;
  for (const double dx : {-0.16, 0.16}) {
    const RigidTransform X_CT = scenes::BoardPose(scene.board, 0.9, 0.0, 0.0, 0.0, dx, 0.0);
    for (const Eigen::Vector3d& p : scene.board_model.corners()) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(scene.projection.Project(X_CT * p, &uv));
      ASSERT_TRUE(dx < 0 ? uv.x() < camera.width / 2 - 10 : uv.x() > camera.width / 2 + 10)
          << "the boards overlap the image's centre line; move them apart";
    }
    const cv::Mat image = scene.renderer.Render(X_CT, 3);
    if (both.empty()) {
      both = image.clone();
    } else {
      const cv::Rect right(camera.width / 2, 0, camera.width - camera.width / 2, camera.height);
      image(right).copyTo(both(right));
    }
  }
  const MeasurePipeline pipeline(scene.board, camera);
  const Measurement m = pipeline.MeasureImage(both, 1);
  EXPECT_NE(m.status, Measurement::Status::kOk);
  EXPECT_NE(m.message.find("36 tag id(s) were seen twice"), std::string::npos) << m.message;
}

TEST(MeasurePipelineTest, WrongFrameTypeIsACameraError) {
  MeasurePipeline pipeline(scenes::PaperBoard(), scenes::PaperCamera());
  Frame frame;
  frame.image = cv::Mat(768, 1024, CV_16U, cv::Scalar(0));
  const std::optional<Measurement> m = pipeline.AddFrame(frame);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->status, Measurement::Status::kCameraError);
}

}  // namespace
}  // namespace h4::cam

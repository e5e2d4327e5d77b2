// What the detector and the pose fit see on real frames (issue 41, point 7): the erosion of
// the tags that the pose fit estimates, and how often the edge fit finds a blur of the pixel
// values on sides along the pixel axes (pixel locking, firmware/detection/edge_refinement.h).
// The frames are the public JPEGs of tests/data/real_frames/README.md (a RealSense D435i's
// colour camera, JPEG quality about 50, Kalibr's aprilgrid); the test skips when they are
// absent, as tests/calibration/real_frames_test.cpp does, whose intrinsics calibration it
// repeats here on all 30 frames. No truth exists for these frames: the checks are
// consistency (the erosion is the camera's and the light's, so the even and the odd frames
// must agree within their spread) and that the refit does not make the pose fit worse.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/camera/camera_model.h"
#include "common/formats/board_yaml.h"
#include "firmware/calibration/board_views.h"
#include "firmware/calibration/intrinsics_calibration.h"
#include "firmware/detection/board_detector.h"
#include "firmware/pose/pose_estimator.h"
#include "tests/calibration/real_frames_helpers.h"

namespace h4::cam {
namespace {

namespace fs = std::filesystem;



struct FrameFile {
  std::string name;
  cv::Mat image;
};

std::vector<FrameFile> ReadFrames(const std::string& dir) {
  std::vector<FrameFile> frames;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".jpg") continue;
    frames.push_back({entry.path().stem().string(),
                      cv::imread(entry.path().string(), cv::IMREAD_GRAYSCALE)});
  }
  std::sort(frames.begin(), frames.end(),
            [](const FrameFile& a, const FrameFile& b) { return a.name < b.name; });
  return frames;
}

struct Mean {
  double sum = 0, sum_sq = 0;
  int n = 0;
  void Add(double x) { sum += x, sum_sq += x * x, ++n; }
  double mean() const { return sum / n; }
  double standard_error() const {
    const double variance = (sum_sq - sum * sum / n) / (n - 1);
    return std::sqrt(std::max(variance, 0.0) / n);
  }
};

TEST(RealFramesPose, ErosionAgreesBetweenHalvesAndThePixelBlurRefitDoesNotWorsenThePose) {
  const std::string dir = RealFramesDir();
  if (dir.empty()) {
    GTEST_SKIP() << "no " << kRealFrameSet
                   << "/ in $H4_REAL_FRAMES_DIR or tests/data/real_frames "
                 << "(tests/data/real_frames/README.md says where to get them)";
  }
  const std::vector<FrameFile> frames = ReadFrames(dir);
  ASSERT_EQ(frames.size(), 30u);
  const BoardSpec board =
      ReadBoardYaml(std::string(H4_SOURCE_DIR) + "/boards/kalibr_aprilgrid_6x6_88mm.yaml");
  const BoardViewFinder finder(board);
  std::vector<CalibrationView> views;
  for (const FrameFile& frame : frames) {
    std::string why;
    if (auto view = finder.Find(frame.image, frame.name, &why)) views.push_back(*view);
  }
  const IntrinsicsCalibrationResult calibration =
      CalibrateIntrinsics(views, frames[0].image.size(), IntrinsicsCalibrationOptions{});
  ASSERT_TRUE(calibration.ok()) << calibration.message;
  const CameraModel camera(calibration.camera);

  DetectorOptions without_refit;
  without_refit.edge_fit.pixel_blur_check_deg = 0.0;
  const BoardDetector detector(board, calibration.camera);
  const BoardDetector detector_without_refit(board, calibration.camera, without_refit);
  std::array<Mean, 2> erosion_by_parity;
  Mean erosion;
  double rms_sq = 0, rms_sq_without = 0;
  int corners = 0, corners_moved = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const BoardDetection detection = detector.Detect(frames[i].image);
    const BoardDetection plain = detector_without_refit.Detect(frames[i].image);
    ASSERT_EQ(detection.status, BoardDetection::Status::kOk) << frames[i].name;
    ASSERT_EQ(detection.corners.size(), plain.corners.size()) << frames[i].name;
    for (size_t k = 0; k < detection.corners.size(); ++k) {
      corners_moved += (detection.corners[k].uv - plain.corners[k].uv).norm() > 1e-3 ? 1 : 0;
    }
    const PoseEstimate pose = EstimatePose(detection.corners, camera);
    const PoseEstimate plain_pose = EstimatePose(plain.corners, camera);
    ASSERT_TRUE(pose.ok() && plain_pose.ok()) << frames[i].name << ": " << pose.message;
    const double n = static_cast<double>(detection.corners.size());
    rms_sq += pose.rms_px * pose.rms_px * n;
    rms_sq_without += plain_pose.rms_px * plain_pose.rms_px * n;
    corners += static_cast<int>(detection.corners.size());
    erosion_by_parity[i % 2].Add(pose.erosion_px);
    erosion.Add(pose.erosion_px);
    std::printf("%s: erosion %+.4f +- %.4f px, pose RMS %.4f px (without the refit %.4f)\n",
                frames[i].name.c_str(), pose.erosion_px, pose.erosion_sigma_px, pose.rms_px,
                plain_pose.rms_px);
  }
  const double rms = std::sqrt(rms_sq / corners), rms_without = std::sqrt(rms_sq_without / corners);
  std::printf(
      "erosion at the image centre: %+.4f px (standard error %.4f) over %d frames; even %+.4f, "
      "odd %+.4f\ncorners the pixel-blur refit moved by more than 0.001 px: %d of %d; pose RMS "
      "%.4f px, without the refit %.4f px\n",
      erosion.mean(), erosion.standard_error(), erosion.n, erosion_by_parity[0].mean(),
      erosion_by_parity[1].mean(), corners_moved, corners, rms, rms_without);
  // The halves differ by less than 3 standard errors of their difference.
  const double se = std::hypot(erosion_by_parity[0].standard_error(),
                               erosion_by_parity[1].standard_error());
  EXPECT_LT(std::abs(erosion_by_parity[0].mean() - erosion_by_parity[1].mean()), 3 * se);
  EXPECT_LE(rms, 1.01 * rms_without);
}

}  // namespace
}  // namespace h4::cam

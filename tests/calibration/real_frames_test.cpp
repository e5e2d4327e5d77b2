// The detector and the intrinsics calibration on real camera frames (issue 28 point 4):
// 30 frames (640 x 480 JPEG) of Kalibr's 6 x 6 tag36h11 aprilgrid (88 mm tags, spacing
// 0.3: boards/kalibr_aprilgrid_6x6_88mm.yaml) taken by an Intel RealSense D435i, with the
// yac calibration toolbox's own detection of each (its corner CSVs), from the MIT-licensed
// repository chutsu/yac (tests/data/real_frames/README.md says where exactly, which commit,
// and under which licence). The frames are not in this repository: the test reads them from
// the first folder that holds them of $H4_REAL_FRAMES_DIR and tests/data/real_frames, each
// with a yac_mocap_d435i/ folder inside, and skips itself, saying so, when none does.
//
// The source publishes no intrinsics, so the camera is calibrated here from the even
// frames (calibrate-intrinsics' path) and the poses are fitted on the odd ones: the
// reprojection RMS of those fits is measured on frames the calibration never saw. The
// tags expected in each frame are those whose whole border is in the image (counted by
// eye on the frames and equal to what the fitted pose predicts with a 3 px margin); the
// four outer corners of the grid are covered by the motion-capture markers glued on the
// board and are left out of the corner comparison with yac.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/formats/board_yaml.h"
#include "firmware/calibration/board_views.h"
#include "firmware/calibration/intrinsics_calibration.h"
#include "firmware/detection/board_detector.h"
#include "firmware/detection/tag_prediction.h"
#include "tests/calibration/real_frames_helpers.h"

namespace h4::cam {
namespace {


// Each frame (its file name less .jpg) with the number of tags whose whole border is in
// the image.
struct Frame {
  const char* name;
  int tags_in_view;
};
const std::array<Frame, 30> kFrames = {{
    {"1606153907495166540", 36}, {"1606153915653051138", 36}, {"1606153921853466272", 36},
    {"1606153950890122890", 24}, {"1606153963139782667", 36}, {"1606153971086688995", 36},
    {"1606153977721161127", 36}, {"1606153983972179413", 36}, {"1606153997421799183", 36},
    {"1606154004360154629", 36}, {"1606154011402862549", 36}, {"1606154017373862028", 36},
    {"1606154022959313869", 36}, {"1606154029409966230", 35}, {"1606154036334099054", 36},
    {"1606154045208428621", 36}, {"1606154057587632418", 36}, {"1606154065240525723", 36},
    {"1606154073179670334", 36}, {"1606154080918648243", 36}, {"1606154091296098471", 36},
    {"1606154103557152987", 36}, {"1606154110540388823", 36}, {"1606154117645546675", 36},
    {"1606154125251100540", 36}, {"1606154131806932688", 36}, {"1606154140441553831", 32},
    {"1606154148298093319", 36}, {"1606154155277716398", 30}, {"1606154165058666229", 36},
}};


BoardSpec Board() {
  return ReadBoardYaml(std::string(H4_SOURCE_DIR) + "/boards/kalibr_aprilgrid_6x6_88mm.yaml");
}

// yac's corners of one frame by h4 corner id: its CSV rows are
// ts,tag_rows,tag_cols,tag_size,tag_spacing,kp_x,kp_y,p_x,p_y,p_z,tag_id,corner_idx with
// Kalibr's corner order, which is the board model's (board_model.h).
std::map<int, Eigen::Vector2d> ReadYacCorners(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  std::map<int, Eigen::Vector2d> corners;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    EXPECT_EQ(v.size(), 12u) << path << ": " << line;
    if (v.size() != 12) continue;
    corners[4 * static_cast<int>(v[10]) + static_cast<int>(v[11])] = Eigen::Vector2d(v[5], v[6]);
  }
  return corners;
}

// The four outer corners of the grid (under the markers): corner 0 of tag 0, 1 of tag 5,
// 3 of tag 30 and 2 of tag 35.
bool OuterGridCorner(int corner_id) {
  return corner_id == 0 || corner_id == 4 * 5 + 1 || corner_id == 4 * 30 + 3 ||
         corner_id == 4 * 35 + 2;
}

class RealFrames : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = RealFramesDir();
    if (dir_.empty()) {
      GTEST_SKIP() << "no " << kRealFrameSet
                   << "/ in $H4_REAL_FRAMES_DIR or tests/data/real_frames "
                   << "(tests/data/real_frames/README.md says where to get them)";
    }
    for (const Frame& frame : kFrames) {
      const std::string path = dir_ + "/" + frame.name + ".jpg";
      images_.push_back(cv::imread(path, cv::IMREAD_GRAYSCALE));
      ASSERT_FALSE(images_.back().empty()) << "cannot read " << path;
      ASSERT_EQ(images_.back().size(), cv::Size(640, 480)) << path;
    }
  }

  // The calibrate-intrinsics path on the frames of the given parity (0 even, 1 odd, -1 all).
  IntrinsicsCalibrationResult Calibrate(int parity) const {
    const BoardViewFinder finder(Board());
    EXPECT_TRUE(finder.ok()) << finder.error();
    std::vector<CalibrationView> views;
    for (size_t i = 0; i < kFrames.size(); ++i) {
      if (parity >= 0 && static_cast<int>(i % 2) != parity) continue;
      std::string why;
      auto view = finder.Find(images_[i], kFrames[i].name, &why);
      EXPECT_TRUE(view) << kFrames[i].name << ": " << why;
      if (view) views.push_back(*view);
    }
    return CalibrateIntrinsics(views, images_[0].size(), IntrinsicsCalibrationOptions{});
  }

  std::string dir_;
  std::vector<cv::Mat> images_;
};

// calibrate-intrinsics (radtan, k1 k2 p1 p2 k3) on all 30 frames and on the 15 even ones:
// every view used, none an outlier, and the RMS reprojection error below 0.34 px (measured
// 0.3192 px and 0.3093 px). With k3 free both fits fold just inside the image's corners
// (404 and 403 px from the principal point, the image reaching 407 and 417 px), which the
// camera file's reader refuses: both are fitted again with k3 held at 0 and say so.
TEST_F(RealFrames, IntrinsicsCalibrationRms) {
  const IntrinsicsCalibrationResult all = Calibrate(-1);
  ASSERT_TRUE(all.ok()) << all.message;
  const IntrinsicsCalibrationResult even = Calibrate(0);
  ASSERT_TRUE(even.ok()) << even.message;
  std::printf("all 30 frames:\n%s\n15 even frames:\n%s\n", all.Report().c_str(),
              even.Report().c_str());
  EXPECT_EQ(all.views_used, 30);
  EXPECT_EQ(even.views_used, 15);
  for (const ViewReport& view : all.views) EXPECT_FALSE(view.outlier) << view.name;
  EXPECT_LT(all.rms_px, 0.34);
  EXPECT_LT(even.rms_px, 0.34);
  for (const IntrinsicsCalibrationResult* result : {&all, &even}) {
    EXPECT_NE(result->message.find("k3 held at 0: with it free, the lens model folds"),
              std::string::npos)
        << result->message;
    EXPECT_EQ(result->camera.distortion[4], 0.0);
  }
  // The even frames' calibration within 3 of its own 1-sigma of the calibration on all 30
  // (measured: fx 591.0 +- 4.5 against 601.8, 2.4 sigma; fy 1.7, cx 0.0, cy 2.0 sigma).
  ASSERT_TRUE(even.camera.intrinsics_covariance.has_value());
  const Eigen::MatrixXd& cov = *even.camera.intrinsics_covariance;
  const std::array<double, 4> even_k = {even.camera.K(0, 0), even.camera.K(1, 1),
                                        even.camera.K(0, 2), even.camera.K(1, 2)};
  const std::array<double, 4> all_k = {all.camera.K(0, 0), all.camera.K(1, 1), all.camera.K(0, 2),
                                       all.camera.K(1, 2)};
  const std::array<const char*, 4> names = {"fx", "fy", "cx", "cy"};
  for (size_t p = 0; p < 4; ++p) {
    const Eigen::Index j = static_cast<Eigen::Index>(p);
    EXPECT_LT(std::abs(even_k[p] - all_k[p]), 3 * std::sqrt(cov(j, j))) << names[p];
  }
}

// The board detector with the camera calibrated on the even frames, on all 30: the tags in
// view found (measured: 1055 of 1057; tag 30 of 1606154065240525723 missed, its code read
// with 2 cells wrong, and tag 35 of 1606154091296098471, read at its predicted place with 5
// code and 3 border cells wrong: the X-corners alone found it, as their pose placed it
// differently), no tag decoded twice, none reported away from where the fitted pose
// puts it, and the tags yac found found too (measured: all but that tag 30 and tag 5 of
// 1606154029409966230, which is not wholly in the image). On the odd frames, which the
// calibration never saw, the RMS of the pose fits (measured 0.3123 px over 2059 corners, at
// most 0.4475 px in one frame; 0.3120 px with the X-corners alone); the largest residual of
// a fit, 1.067 px at an inner corner (3.736 px at an outer grid corner, under a marker).
TEST_F(RealFrames, BoardDetectorTagsAndHeldOutPoseRms) {
  const IntrinsicsCalibrationResult even = Calibrate(0);
  ASSERT_TRUE(even.ok()) << even.message;
  const BoardSpec spec = Board();
  const BoardModel board(spec);
  const CameraModel camera(even.camera);
  const BoardDetector detector(spec, even.camera);
  ASSERT_TRUE(detector.ok()) << detector.error();
  int expected = 0, found = 0, yac_tags = 0, yac_tags_missed = 0;
  double held_out_sq = 0;
  int held_out_corners = 0;
  double largest_inner_px = 0, largest_outer_px = 0;
  for (size_t i = 0; i < kFrames.size(); ++i) {
    const Frame& frame = kFrames[i];
    const BoardDetection detection = detector.Detect(images_[i]);
    EXPECT_EQ(detection.status, BoardDetection::Status::kOk) << frame.name;
    EXPECT_EQ(detection.ids_seen_twice, 0) << frame.name;
    RigidTransform X_CT;
    double rms_px = 0;
    ASSERT_TRUE(FitPoseToCorners(detection.corners, camera, &X_CT, &rms_px)) << frame.name;
    // Tags in view by the pose agree with the count by eye.
    int in_view = 0;
    for (int t = 0; t < board.corner_count() / 4; ++t) {
      std::array<Eigen::Vector2d, 4> corners_px;
      in_view += PredictTagCorners(board, camera, X_CT, t, 3.0, &corners_px) ? 1 : 0;
    }
    EXPECT_EQ(in_view, frame.tags_in_view) << frame.name;
    std::set<int> tags;
    for (const CornerObservation& c : detection.corners) {
      tags.insert(c.id / 4);
      std::array<Eigen::Vector2d, 4> tag_px;
      Eigen::Vector2d uv;
      ASSERT_TRUE(camera.ProjectRay(X_CT * c.p_TQ, &uv)) << frame.name;
      ASSERT_TRUE(PredictTagCorners(board, camera, X_CT, c.id / 4, -1e3, &tag_px)) << frame.name;
      double side_px = 1e9;
      for (size_t k = 0; k < 4; ++k) {
        side_px = std::min(side_px, (tag_px[k] - tag_px[(k + 1) % 4]).norm());
      }
      // A corner a third of its tag's side or more from the pose's projection is on another
      // tag or is another corner: a wrong tag.
      const double residual_px = (uv - c.uv).norm();
      EXPECT_LT(residual_px, side_px / 3) << frame.name << " corner " << c.id;
      double& largest = OuterGridCorner(c.id) ? largest_outer_px : largest_inner_px;
      largest = std::max(largest, residual_px);
    }
    EXPECT_EQ(static_cast<int>(tags.size()), detection.tags) << frame.name;
    EXPECT_GE(detection.tags, frame.tags_in_view - 1) << frame.name;
    expected += frame.tags_in_view;
    found += std::min(detection.tags, frame.tags_in_view);
    std::set<int> yac;
    for (const auto& [id, uv] : ReadYacCorners(dir_ + "/yac/" + frame.name + ".csv")) {
      yac.insert(id / 4);
    }
    for (int t : yac) yac_tags_missed += tags.count(t) ? 0 : 1;
    yac_tags += static_cast<int>(yac.size());
    std::printf("%s: %d of %d tags in view (%d predicted), yac %zu, pose RMS %.4f px%s\n",
                frame.name, detection.tags, frame.tags_in_view, detection.tags_predicted,
                yac.size(), rms_px, i % 2 ? " (held out)" : "");
    if (i % 2 == 1) {
      held_out_sq += rms_px * rms_px * static_cast<double>(detection.corners.size());
      held_out_corners += static_cast<int>(detection.corners.size());
      EXPECT_LT(rms_px, 0.48) << frame.name;  // measured at most 0.4475 px
    }
  }
  const double held_out_rms = std::sqrt(held_out_sq / held_out_corners);
  std::printf(
      "tags found %d of %d in view; yac found %d, %d of them not found here; held-out "
      "pose RMS %.4f px over %d corners\n",
      found, expected, yac_tags, yac_tags_missed, held_out_rms, held_out_corners);
  std::printf(
      "largest residual of a pose fit: %.3f px at an inner corner, %.3f px at an outer "
      "grid corner\n",
      largest_inner_px, largest_outer_px);
  EXPECT_GE(found, expected - 2);
  // yac's two that are not found here: tag 5 of 1606154029409966230, not wholly in the
  // image, and tag 30 of 1606154065240525723, the one whose code failed here.
  EXPECT_LE(yac_tags_missed, 2);
  EXPECT_LT(held_out_rms, 0.33);
  EXPECT_LT(largest_inner_px, 1.25);
}

// The corners found here against yac's (an independent detector; its CSVs were published
// with the frames, whether from these JPEGs or from the images they were compressed from
// is not said), the four outer grid corners left out: no offset between the two (a
// pixel-convention error would show half a pixel) and close agreement (measured: mean
// offset (-0.0025, 0.0062) px, median distance 0.0908 px, 90th percentile 0.2175 px over
// 3885 corners; with the X-corners alone 0.0888 and 0.2061 px).
TEST_F(RealFrames, CornersAgreeWithYac) {
  const IntrinsicsCalibrationResult even = Calibrate(0);
  ASSERT_TRUE(even.ok()) << even.message;
  const BoardDetector detector(Board(), even.camera);
  ASSERT_TRUE(detector.ok()) << detector.error();
  std::vector<double> distances;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < kFrames.size(); ++i) {
    const auto yac = ReadYacCorners(dir_ + "/yac/" + kFrames[i].name + ".csv");
    for (const CornerObservation& c : detector.Detect(images_[i]).corners) {
      const auto it = yac.find(c.id);
      if (it == yac.end() || OuterGridCorner(c.id)) continue;
      distances.push_back((c.uv - it->second).norm());
      offset += c.uv - it->second;
    }
  }
  ASSERT_FALSE(distances.empty());
  offset /= static_cast<double>(distances.size());
  std::sort(distances.begin(), distances.end());
  const double median = distances[distances.size() / 2];
  const double p90 = distances[distances.size() * 9 / 10];
  std::printf(
      "%zu corners compared: mean offset (%.4f, %.4f) px, median %.4f px, 90th "
      "percentile %.4f px, largest %.4f px\n",
      distances.size(), offset.x(), offset.y(), median, p90, distances.back());
  EXPECT_GT(distances.size(), 3800u);
  EXPECT_LT(std::abs(offset.x()), 0.02);
  EXPECT_LT(std::abs(offset.y()), 0.02);
  EXPECT_LT(median, 0.10);
  EXPECT_LT(p90, 0.23);
}

}  // namespace
}  // namespace h4::cam

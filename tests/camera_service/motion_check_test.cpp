// Tests for firmware/averaging: the float mean of a group, and the motion check that
// flags a group in which the board moved.
#include "firmware/averaging/motion_check.h"

#include <gtest/gtest.h>

#include "firmware/averaging/frame_averager.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {
namespace {

TEST(FrameAveragerTest, MeanKeepsFractionsOfAGreyLevel) {
  FrameAverager averager(4);
  for (int k = 0; k < 4; ++k) {
    Frame frame;
    frame.image = cv::Mat(2, 3, CV_8U, cv::Scalar(k == 0 ? 11 : 10));
    frame.utime = 100 + k;
    ASSERT_TRUE(averager.Add(frame));
  }
  EXPECT_TRUE(averager.complete());
  EXPECT_EQ(averager.first_utime(), 100);
  const cv::Mat mean = averager.Mean();
  ASSERT_EQ(mean.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(mean.at<float>(1, 2), 10.25f);
}

TEST(FrameAveragerTest, FrameOfAnotherSizeIsRefused) {
  FrameAverager averager(3);
  Frame a, b;
  a.image = cv::Mat(4, 4, CV_8U, cv::Scalar(1));
  b.image = cv::Mat(5, 4, CV_8U, cv::Scalar(1));
  ASSERT_TRUE(averager.Add(a));
  EXPECT_FALSE(averager.Add(b));
  EXPECT_NE(averager.error().find("differs"), std::string::npos);
  EXPECT_EQ(averager.count(), 1);
}

// Measures one group of 10 frames from the sim source; the board moves by `step` (m,
// along x in C) after the 5th frame.
Measurement MeasureGroup(double step) {
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  SimSource source(board, camera, SimSourceOptions{});
  EXPECT_TRUE(source.Open());
  const RigidTransform X_CT = scenes::BoardPose(board, 0.55, 0.25, 0.4, 0.3);
  MeasurePipeline pipeline(board, camera);
  source.SetPose(X_CT);
  std::optional<Measurement> m;
  for (int k = 0; k < 10; ++k) {
    if (k == 5) {
      source.SetPose(
          RigidTransform(X_CT.rotation(), X_CT.translation() + Eigen::Vector3d(step, 0, 0)));
    }
    m = pipeline.AddFrame(*source.Next(std::chrono::milliseconds(0)));
    if (k < 9) {
      EXPECT_FALSE(m.has_value());
    }
  }
  EXPECT_TRUE(m.has_value());
  return m.value_or(Measurement{});
}

TEST(MotionCheckTest, StillBoardIsNotFlagged) {
  const Measurement m = MeasureGroup(0.0);
  EXPECT_EQ(m.status, Measurement::Status::kOk) << m.message;
  EXPECT_LT(m.frame_spread_px, 0.02);  // measured ~0.002 px with noise 2
  EXPECT_EQ(m.frames_averaged, 10);
}

TEST(MotionCheckTest, BoardMovingHalfwayThroughTheGroupIsFlaggedMoved) {
  // 0.2 mm at 0.55 m is 0.3 px: each half sits 0.15 px from the mean.
  const Measurement m = MeasureGroup(0.0002);
  EXPECT_EQ(m.status, Measurement::Status::kMoved);
  EXPECT_NEAR(m.frame_spread_px, 0.15, 0.05);
  EXPECT_NE(m.message.find("moved"), std::string::npos);
}

TEST(MotionCheckTest, LargeJumpIsFlaggedMoved) {
  const Measurement m = MeasureGroup(0.002);  // 3 px
  EXPECT_NE(m.status, Measurement::Status::kOk);
}

}  // namespace
}  // namespace h4::cam

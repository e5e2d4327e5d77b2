// Every message type encodes and decodes to the same values (generated code from
// lcm-gen at build time), and a truncated buffer is rejected rather than misread.
#include <vector>

#include <gtest/gtest.h>

#include "h4msgs/board_pose_t.hpp"
#include "h4msgs/camera_status_t.hpp"
#include "h4msgs/capture_request_t.hpp"
#include "h4msgs/joint_state_t.hpp"
#include "h4msgs/robot_target_t.hpp"
#include "h4msgs/sim_board_truth_t.hpp"

#include "tests/messages/wire_bytes.h"

namespace {

// lcm-gen 1.3.1 declares message constants `static const` without a definition, so they
// must not be bound to references (gtest's EXPECT_EQ does): compare copies as int.

template <typename Msg>
Msg RoundTrip(const Msg& in) {
  std::vector<uint8_t> buffer(static_cast<size_t>(in.getEncodedSize()));
  EXPECT_EQ(in.encode(buffer.data(), 0, static_cast<int>(buffer.size())),
            static_cast<int>(buffer.size()));
  Msg out;
  EXPECT_EQ(out.decode(buffer.data(), 0, static_cast<int>(buffer.size())),
            static_cast<int>(buffer.size()));
  // A truncated buffer must fail to decode.
  Msg truncated;
  EXPECT_LT(truncated.decode(buffer.data(), 0, static_cast<int>(buffer.size()) - 1), 0);
  return out;
}

TEST(Messages, BoardPoseRoundTrips) {
  const h4msgs::board_pose_t m = h4::bus::wire_bytes::FullBoardPose();
  const auto out = RoundTrip(m);
  EXPECT_EQ(out.utime, m.utime);
  EXPECT_EQ(out.pose_id, m.pose_id);
  EXPECT_EQ(out.camera_id, m.camera_id);
  EXPECT_EQ(out.board_id, m.board_id);
  EXPECT_DOUBLE_EQ(out.translation[2], m.translation[2]);
  EXPECT_DOUBLE_EQ(out.covariance[35], m.covariance[35]);
  EXPECT_EQ(out.corners_used, m.corners_used);
  EXPECT_DOUBLE_EQ(out.frame_spread_px, m.frame_spread_px);
  EXPECT_EQ(int{out.status}, int{h4msgs::board_pose_t::STATUS_MOVED});
}

TEST(Messages, JointStateRoundTripsVariableLength) {
  h4msgs::joint_state_t m{};
  m.utime = 5;
  m.pose_id = 7;
  m.joint_count = 4;
  m.position = {3.1, -3.1, 0.5, -0.5};
  m.settled = true;
  const auto out = RoundTrip(m);
  EXPECT_EQ(out.joint_count, 4);
  EXPECT_EQ(out.position, m.position);
  EXPECT_TRUE(out.settled);
}

TEST(Messages, CaptureRequestRoundTrips) {
  h4msgs::capture_request_t m{};
  m.utime = 9;
  m.pose_id = 80;
  m.frame_count = 10;
  const auto out = RoundTrip(m);
  EXPECT_EQ(out.pose_id, 80);
  EXPECT_EQ(out.frame_count, 10);
}

TEST(Messages, CameraStatusRoundTrips) {
  h4msgs::camera_status_t m{};
  m.utime = 11;
  m.camera_id = "sim";
  m.state = h4msgs::camera_status_t::STATE_ERROR;
  m.frame_rate_hz = 30.0;
  m.exposure_us = 8000;
  m.analogue_gain = 1.5;
  m.frames_total = 1000;
  m.measurements_total = 12;
  m.last_error = "device timeout";
  const auto out = RoundTrip(m);
  EXPECT_EQ(int{out.state}, int{h4msgs::camera_status_t::STATE_ERROR});
  EXPECT_EQ(out.last_error, "device timeout");
  EXPECT_DOUBLE_EQ(out.analogue_gain, 1.5);
  EXPECT_EQ(out.measurements_total, 12);
}

TEST(Messages, RobotTargetRoundTrips) {
  h4msgs::robot_target_t m{};
  m.utime = 13;
  m.pose_id = 3;
  m.target_type = h4msgs::robot_target_t::TARGET_JOINTS;
  m.joints[3] = -2.5;
  m.pose[2] = -0.45;
  const auto out = RoundTrip(m);
  EXPECT_EQ(int{out.target_type}, int{h4msgs::robot_target_t::TARGET_JOINTS});
  EXPECT_DOUBLE_EQ(out.joints[3], -2.5);
  EXPECT_DOUBLE_EQ(out.pose[2], -0.45);
}

TEST(Messages, SimBoardTruthRoundTrips) {
  h4msgs::sim_board_truth_t m{};
  m.utime = 17;
  m.pose_id = 1;
  m.translation[1] = 0.02;
  m.quaternion[0] = 1.0;
  m.settled = true;
  const auto out = RoundTrip(m);
  EXPECT_DOUBLE_EQ(out.translation[1], 0.02);
  EXPECT_TRUE(out.settled);
}

TEST(Messages, FingerprintMismatchIsRejected) {
  // Decoding one type's bytes as another must fail (LCM's type hash check).
  h4msgs::capture_request_t req{};
  std::vector<uint8_t> buffer(static_cast<size_t>(req.getEncodedSize()));
  req.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  h4msgs::robot_target_t target;
  EXPECT_LT(target.decode(buffer.data(), 0, static_cast<int>(buffer.size())), 0);
}

}  // namespace

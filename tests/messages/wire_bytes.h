// Test helpers shared by the message and bus tests: valid board poses, a message's LCM wire
// bytes, and a big-endian write into them (to forge the lengths and counts a hostile sender
// would).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "h4msgs/board_pose_t.hpp"

namespace h4::bus::wire_bytes {

/// A board pose with every field set (a real camera id, the whole covariance, status
/// moved): the round-trip and layout tests see each field on the wire.
inline h4msgs::board_pose_t FullBoardPose() {
  h4msgs::board_pose_t m{};
  m.utime = 1700000000123456;
  m.pose_id = 42;
  m.camera_id = "/base/soc/i2c0mux/i2c@1/imx477@1a";
  m.board_id = "aprilgrid_6x6_30mm";
  m.translation[0] = 0.01;
  m.translation[2] = 0.55;
  m.quaternion[0] = 1.0;
  for (int i = 0; i < 36; ++i) m.covariance[i] = i * 1e-9;
  m.frames_averaged = 10;
  m.corners_used = 144;
  m.reprojection_rms_px = 0.05;
  m.frame_spread_px = 0.2;
  m.status = h4msgs::board_pose_t::STATUS_MOVED;
  return m;
}

/// A valid board pose of camera "sim" and board "board" (the identity rotation, the other
/// fields zero).
inline h4msgs::board_pose_t SampleBoardPose(int64_t pose_id,
                                            int64_t utime = 1700000000000000) {
  h4msgs::board_pose_t m{};
  m.utime = utime;
  m.pose_id = pose_id;
  m.camera_id = "sim";
  m.board_id = "board";
  m.quaternion[0] = 1.0;
  return m;
}

template <class Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return bytes;
}

inline void PutBigEndian32(std::vector<uint8_t>* bytes, size_t pos, int32_t value) {
  const auto u = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) (*bytes)[pos + static_cast<size_t>(i)] = uint8_t(u >> (24 - 8 * i));
}

}  // namespace h4::bus::wire_bytes

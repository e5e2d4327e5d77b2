// The wire layout of each h4msgs type (messages/*.lcm, field by field, in file order), for
// the check that runs before lcm-gen's decode() (wire_check.h). The bus adapter refuses to
// subscribe to a type without one (a compile error), and messages_test checks each against
// the generated encoder (same size for every message it encodes), so a field added to a
// .lcm file and not here fails the tests.
#pragma once

#include "h4msgs/board_pose_t.hpp"
#include "h4msgs/camera_status_t.hpp"
#include "h4msgs/capture_request_t.hpp"
#include "h4msgs/joint_state_t.hpp"
#include "h4msgs/robot_target_t.hpp"
#include "h4msgs/sim_board_truth_t.hpp"

#include "messages/bus/wire_check.h"

namespace h4::bus {

/// Specialised below for every type of messages/; deliberately not defined otherwise.
template <class Msg>
const WireLayout& LayoutOf();

namespace wire {
inline WireField Int8(const char* name) { return {name, WireKind::kInt8, 1, -1}; }
inline WireField Int32(const char* name) { return {name, WireKind::kInt32, 1, -1}; }
inline WireField Int64(const char* name) { return {name, WireKind::kInt64, 1, -1}; }
inline WireField Doubles(const char* name, int count) {
  return {name, WireKind::kDouble, count, -1};
}
inline WireField String(const char* name) { return {name, WireKind::kString, 1, -1}; }
/// Doubles counted by the int32 field at `count_field` (its index in the layout).
inline WireField CountedDoubles(const char* name, int count_field) {
  return {name, WireKind::kDouble, 1, count_field};
}
}  // namespace wire

template <>
inline const WireLayout& LayoutOf<h4msgs::board_pose_t>() {
  using namespace wire;
  static const WireLayout layout{
      "h4msgs.board_pose_t",
      h4msgs::board_pose_t::getHash(),
      {Int64("utime"), Int64("pose_id"), String("camera_id"), String("board_id"),
       Doubles("translation", 3), Doubles("quaternion", 4), Doubles("covariance", 36),
       Int32("frames_averaged"), Int32("corners_used"), Doubles("reprojection_rms_px", 1),
       Doubles("frame_spread_px", 1), Int8("status")}};
  return layout;
}

template <>
inline const WireLayout& LayoutOf<h4msgs::camera_status_t>() {
  using namespace wire;
  static const WireLayout layout{
      "h4msgs.camera_status_t",
      h4msgs::camera_status_t::getHash(),
      {Int64("utime"), String("camera_id"), Int8("state"), Doubles("frame_rate_hz", 1),
       Doubles("exposure_us", 1), Doubles("analogue_gain", 1), Int64("frames_total"),
       Int64("measurements_total"), String("last_error")}};
  return layout;
}

template <>
inline const WireLayout& LayoutOf<h4msgs::capture_request_t>() {
  using namespace wire;
  static const WireLayout layout{"h4msgs.capture_request_t",
                                 h4msgs::capture_request_t::getHash(),
                                 {Int64("utime"), Int64("pose_id"), Int32("frame_count")}};
  return layout;
}

template <>
inline const WireLayout& LayoutOf<h4msgs::joint_state_t>() {
  using namespace wire;
  static const WireLayout layout{"h4msgs.joint_state_t",
                                 h4msgs::joint_state_t::getHash(),
                                 {Int64("utime"), Int64("pose_id"), Int32("joint_count"),
                                  CountedDoubles("position", 2), Int8("settled")}};
  return layout;
}

template <>
inline const WireLayout& LayoutOf<h4msgs::robot_target_t>() {
  using namespace wire;
  static const WireLayout layout{"h4msgs.robot_target_t",
                                 h4msgs::robot_target_t::getHash(),
                                 {Int64("utime"), Int64("pose_id"), Int8("target_type"),
                                  Doubles("pose", 4), Doubles("joints", 4)}};
  return layout;
}

template <>
inline const WireLayout& LayoutOf<h4msgs::sim_board_truth_t>() {
  using namespace wire;
  static const WireLayout layout{"h4msgs.sim_board_truth_t",
                                 h4msgs::sim_board_truth_t::getHash(),
                                 {Int64("utime"), Int64("pose_id"), Doubles("translation", 3),
                                  Doubles("quaternion", 4), Int8("settled")}};
  return layout;
}

}  // namespace h4::bus

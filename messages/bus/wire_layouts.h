// The wire layout of each h4msgs type (messages/*.lcm, field by field, in file order), for
// the check that runs before lcm-gen's decode() (wire_check.h). The bus adapter refuses to
// subscribe to a type without one (a compile error), and messages_test checks each against
// the generated encoder (same size for every message it encodes), so a field added to a
// .lcm file and not here fails the tests.
#pragma once

#include <string>
#include <vector>

#include "h4msgs/board_corners_t.hpp"
#include "h4msgs/board_pose_t.hpp"
#include "h4msgs/camera_status_t.hpp"
#include "h4msgs/capture_request_t.hpp"
#include "h4msgs/joint_state_t.hpp"
#include "h4msgs/robot_target_t.hpp"
#include "h4msgs/sim_board_truth_t.hpp"
#include "h4msgs/target_status_t.hpp"

#include "messages/bus/wire_check.h"

namespace h4::bus {

/// The fields of Msg on the wire, in the .lcm file's order. Specialised below for every type
/// of messages/; deliberately not defined otherwise.
template <class Msg>
std::vector<WireField> WireFieldsOf();

/// Msg's layout: its lcm type name ("h4msgs.board_pose_t"), the fingerprint lcm-gen
/// computed from the .lcm file, and WireFieldsOf<Msg>.
template <class Msg>
const WireLayout& LayoutOf() {
  static const std::string type_name = std::string("h4msgs.") + Msg::getTypeName();
  static const WireLayout layout{type_name.c_str(), Msg::getHash(), WireFieldsOf<Msg>()};
  return layout;
}

namespace wire {
inline WireField Int8(const char* name) { return {name, WireKind::kInt8, 1, -1}; }
inline WireField Int32(const char* name) { return {name, WireKind::kInt32, 1, -1}; }
inline WireField Int64(const char* name) { return {name, WireKind::kInt64, 1, -1}; }
inline WireField Doubles(const char* name, int count) {
  return {name, WireKind::kDouble, count, -1};
}
inline WireField String(const char* name) { return {name, WireKind::kString, 1, -1}; }
/// Doubles counted by the int32 field at `count_field` (its index in the layout), at most
/// `max_count` of them (0: WireLimits::max_array_length).
inline WireField CountedDoubles(const char* name, int count_field, int max_count = 0) {
  return {name, WireKind::kDouble, 1, count_field, max_count};
}
inline WireField CountedInt32s(const char* name, int count_field, int max_count = 0) {
  return {name, WireKind::kInt32, 1, count_field, max_count};
}
}  // namespace wire

/// Corners one board_corners_t may carry (its MAX_CORNERS: within the 64 KiB of
/// WireLimits::max_message_bytes).
inline constexpr int kMaxBoardCorners = h4msgs::board_corners_t::MAX_CORNERS;

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::board_corners_t>() {
  using namespace wire;
  constexpr int kCount = 3;  // index of corner_count
  return std::vector<WireField>(
      {Int64("utime"), Int64("pose_id"), String("camera_id"), Int32("corner_count"),
       CountedInt32s("tag_id", kCount, kMaxBoardCorners),
       CountedInt32s("corner", kCount, kMaxBoardCorners),
       CountedDoubles("u", kCount, kMaxBoardCorners), CountedDoubles("v", kCount, kMaxBoardCorners),
       CountedDoubles("sigma_px", kCount, kMaxBoardCorners)});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::board_pose_t>() {
  using namespace wire;
  return std::vector<WireField>(
      {Int64("utime"), Int64("pose_id"), String("camera_id"), String("board_id"),
       Doubles("translation", 3), Doubles("quaternion", 4), Doubles("covariance", 36),
       Int32("frames_averaged"), Int32("corners_used"), Doubles("reprojection_rms_px", 1),
       Doubles("frame_spread_px", 1), Int8("status")});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::camera_status_t>() {
  using namespace wire;
  return std::vector<WireField>({Int64("utime"), String("camera_id"), Int8("state"),
                                 Doubles("frame_rate_hz", 1), Doubles("exposure_us", 1),
                                 Doubles("analogue_gain", 1), Int64("frames_total"),
                                 Int64("measurements_total"), String("last_error")});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::capture_request_t>() {
  using namespace wire;
  return std::vector<WireField>({Int64("utime"), Int64("pose_id"), Int32("frame_count")});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::joint_state_t>() {
  using namespace wire;
  return std::vector<WireField>({Int64("utime"), Int64("pose_id"), Int32("joint_count"),
                                 CountedDoubles("position", 2), Int8("settled")});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::robot_target_t>() {
  using namespace wire;
  return std::vector<WireField>({Int64("utime"), Int64("pose_id"), Int8("target_type"),
                                 Doubles("pose", 4), Doubles("joints", 4)});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::sim_board_truth_t>() {
  using namespace wire;
  return std::vector<WireField>({Int64("utime"), Int64("pose_id"), Doubles("translation", 3),
                                 Doubles("quaternion", 4), Int8("settled")});
}

template <>
inline std::vector<WireField> WireFieldsOf<h4msgs::target_status_t>() {
  using namespace wire;
  return std::vector<WireField>(
      {Int64("utime"), Int64("pose_id"), Int8("status"), String("reason")});
}

}  // namespace h4::bus

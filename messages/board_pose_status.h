// A measurement's status on the wire: board_pose_t's `status` byte carries the number of
// h4::BoardPoseStatus (common/board/board_pose_status.h), checked here against the
// STATUS_ constants of messages/board_pose_t.lcm.
#pragma once

#include <cstdint>
#include <optional>

#include <h4msgs/board_pose_t.hpp>

#include "common/board/board_pose_status.h"

namespace h4 {

static_assert(static_cast<int8_t>(BoardPoseStatus::kOk) == h4msgs::board_pose_t::STATUS_OK);
static_assert(static_cast<int8_t>(BoardPoseStatus::kNoBoard) ==
              h4msgs::board_pose_t::STATUS_NO_BOARD);
static_assert(static_cast<int8_t>(BoardPoseStatus::kMoved) == h4msgs::board_pose_t::STATUS_MOVED);
static_assert(static_cast<int8_t>(BoardPoseStatus::kPartial) ==
              h4msgs::board_pose_t::STATUS_PARTIAL);
static_assert(static_cast<int8_t>(BoardPoseStatus::kCameraError) ==
              h4msgs::board_pose_t::STATUS_CAMERA_ERROR);

constexpr int8_t ToWire(BoardPoseStatus status) { return static_cast<int8_t>(status); }

/// The status a board_pose_t's `status` byte carries; nullopt for a number no camera sends.
constexpr std::optional<BoardPoseStatus> BoardPoseStatusFromWire(int8_t status) {
  if (status < 0 || status >= static_cast<int8_t>(kBoardPoseStatusNames.kCount)) {
    return std::nullopt;
  }
  return static_cast<BoardPoseStatus>(status);
}

}  // namespace h4

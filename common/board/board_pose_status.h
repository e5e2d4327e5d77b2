// What one measurement of the board by the camera module came to. The values are those of
// board_pose_t's STATUS_ constants on the wire (messages/board_pose_status.h checks them):
// the camera measures with them, and the host names what it receives with the same words.
#pragma once

#include <cstdint>

#include "common/text/enum_names.h"

namespace h4 {

enum class BoardPoseStatus : int8_t {
  kOk = 0,           ///< pose valid
  kNoBoard = 1,      ///< no board detected
  kMoved = 2,        ///< the board moved during the group of frames
  kPartial = 3,      ///< too few corners for a reliable pose
  kCameraError = 4,  ///< capture failed
};

inline constexpr EnumNames<BoardPoseStatus, BoardPoseStatus::kCameraError> kBoardPoseStatusNames = {
    "ok", "no board", "moved", "partial", "camera error"};

/// "ok", "no board", "moved", "partial", "camera error".
constexpr const char* ToString(BoardPoseStatus status) {
  return kBoardPoseStatusNames.NameOf(status);
}

}  // namespace h4

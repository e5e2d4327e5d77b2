// A measurement's status on the wire (messages/board_pose_status.h): every status goes out
// as its board_pose_t number and comes back as itself; other numbers are no status.
#include "messages/board_pose_status.h"

#include <gtest/gtest.h>

namespace h4 {
namespace {

TEST(BoardPoseStatusWire, EveryStatusRoundTripsThroughItsNumber) {
  for (BoardPoseStatus status :
       {BoardPoseStatus::kOk, BoardPoseStatus::kNoBoard, BoardPoseStatus::kMoved,
        BoardPoseStatus::kPartial, BoardPoseStatus::kCameraError}) {
    EXPECT_EQ(BoardPoseStatusFromWire(ToWire(status)), status) << ToString(status);
  }
  EXPECT_EQ(int{ToWire(BoardPoseStatus::kMoved)}, int{h4msgs::board_pose_t::STATUS_MOVED});
}

TEST(BoardPoseStatusWire, ANumberNoCameraSendsIsNoStatus) {
  EXPECT_FALSE(BoardPoseStatusFromWire(-1));
  EXPECT_FALSE(BoardPoseStatusFromWire(5));
  EXPECT_FALSE(BoardPoseStatusFromWire(127));
}

}  // namespace
}  // namespace h4

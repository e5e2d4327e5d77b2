// Channel names on the bus (messages/README.md lists who publishes each).
#pragma once

namespace h4::channels {
inline constexpr const char* kBoardPose = "H4_BOARD_POSE";
inline constexpr const char* kBoardCorners = "H4_BOARD_CORNERS";
inline constexpr const char* kJointState = "H4_JOINT_STATE";
inline constexpr const char* kCaptureRequest = "H4_CAPTURE_REQUEST";
inline constexpr const char* kCameraStatus = "H4_CAMERA_STATUS";
inline constexpr const char* kRobotTarget = "H4_ROBOT_TARGET";
inline constexpr const char* kTargetStatus = "H4_TARGET_STATUS";
inline constexpr const char* kSimBoardTruth = "H4_SIM_BOARD_TRUTH";
}  // namespace h4::channels

// Where the public real frames of tests/data/real_frames/README.md are: shared by the tests
// that use them (tests/calibration/real_frames_test.cpp, tests/h4cam_cli/real_frames_pose_test.cpp).
#pragma once

#include <string>

namespace h4::cam {

/// The frame set's folder name.
inline const std::string kRealFrameSet = "yac_mocap_d435i";

/// The set's folder in $H4_REAL_FRAMES_DIR or tests/data/real_frames, in that order, or ""
/// when neither holds it (the tests then skip themselves).
std::string RealFramesDir();

}  // namespace h4::cam

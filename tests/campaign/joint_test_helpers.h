// Test helper of the simulated controller tests: how far apart two joint vectors are, each
// joint's difference wrapped to (-pi, pi] (the encoders read angles modulo a turn).
#pragma once

#include <algorithm>
#include <cmath>

#include "common/geometry/rotation.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// The largest |a_i - b_i| over the four joints, each wrapped to (-pi, pi].
inline double MaxWrappedJointDifference(const JointVector& a, const JointVector& b) {
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) worst = std::max(worst, std::abs(WrapAngle(a[i] - b[i])));
  return worst;
}

}  // namespace h4::host

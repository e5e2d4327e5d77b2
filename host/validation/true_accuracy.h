// Accuracy against a simulated truth, the figure no camera can fake: each pose commanded
// through the identified model's inverse kinematics, reached by the true robot's forward
// kinematics, after the best rigid registration of the base frame
// (ResidualAfterRigidRegistration: a base frame is a convention, the robot's shape is not).
// For studies and tests on simulated robots; a real robot has no truth to compare with.
#pragma once

#include <vector>

#include "host/formats/identification_result.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

struct TrueAccuracy {
  int poses = 0;                ///< commanded poses both models reach
  double position_rms_m = 0.0;  ///< registered position error, RMS over the poses
  double position_max_m = 0.0;
  double z_scale_ppm = 0.0;  ///< slope of the registered Z error against the commanded Z
};

/// `commanded_B`: end-effector poses in Model 12's B (a pose plan); mapped to the result's
/// base frame (B31 for a Model 31 result) as the identification maps them.
TrueAccuracy TrueAccuracyOfResult(const IdentificationResult& result, const SimulatedRobot& truth,
                                  const std::vector<EePose>& commanded_B);

}  // namespace h4::host

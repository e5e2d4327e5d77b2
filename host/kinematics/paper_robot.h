// The robot of the reference paper (Renaud et al., ICRA 2003): Table 2's a priori and
// "Identified" Model 12 parameters, and a default camera/board placement consistent with
// common/formats/README.md's robot.yaml example (camera 1.05 m below the base looking up at the
// board under the nacelle).
#pragma once

#include <numbers>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// Table 2, first rows (a priori), SI. d is not in Table 2; its a priori is 0.
inline const Model12Parameters kPaperAprioriModel12{
    .h = 0.060,
    .arm = 0.2600,
    .forearm = 0.4800,
    .R = 0.1400,
    .d = 0.0,
    .alpha = {0.0, 3.1416, 4.7124, 4.7124},
    .q0 = {0.0, 0.0, 0.0, 0.0},
};

/// Table 2, "Identified" rows, SI.
inline const Model12Parameters kPaperIdentifiedModel12{
    .h = 0.0610,
    .arm = 0.2600,
    .forearm = 0.4876,
    .R = 0.1413,
    .d = 0.0,
    .alpha = {-0.0015, 3.1016, 4.6807, 4.6859},
    .q0 = {-0.0662, -0.0080, -0.0476, -0.0561},
};

/// Camera in B: 1.05 m below the base plane, optical axis z_C = z_B (up, towards the
/// nacelle), x_C = x_B. The board is then 0.50-0.65 m in front of the camera over the grid.
inline RigidTransform PaperX_BC() {
  return RigidTransform(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.0, -1.05));
}

/// End-effector in the board frame: E sits over the centre of a ~0.18 m board, 25 mm
/// behind its printed face (z_T = z_B points away from the camera, the printed face looks
/// down at it).
inline RigidTransform PaperX_TE() {
  return RigidTransform(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.09, 0.09, 0.025));
}

/// The paper's a priori robot description (Table 2 a priori, default placement).
RobotDescription PaperAprioriRobot();

}  // namespace h4::host

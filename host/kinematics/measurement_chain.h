// The measurement chain of the paper's eq. (6), X_BE = X_BC * X_CT * X_TE: the end-effector
// pose (X, Y, Z, theta) a camera measurement X_CT implies, with the tilt that the 4-DoF
// hypothesis says should vanish, and the board pose an end-effector pose predicts.
#pragma once

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// X_BE = (Rz(theta), [X, Y, Z]).
RigidTransform TransformFromEePose(const EePose& x);

/// (X, Y, Z) = p_BE, theta = atan2(R_BE(1,0), R_BE(0,0)) (common/README.md). When `tilt` is
/// given it receives the rotation vector of Rz(theta)^T R_BE (rad, in E): what remains of
/// R_BE after the rotation about z_B, zero for an ideal 4-DoF robot.
EePose EePoseFromTransform(const RigidTransform& X_BE, Eigen::Vector3d* tilt = nullptr);

/// The end-effector pose a measurement implies: X_BE = X_BC * X_CT * X_TE (eq. (6)).
struct MeasuredEePose {
  EePose x = EePose::Zero();                       ///< (X, Y, Z, theta) in B, m and rad
  Eigen::Vector3d tilt = Eigen::Vector3d::Zero();  ///< rotation vector of Rz(theta)^T R_BE, rad
  double tilt_angle = 0.0;                         ///< |tilt|, rad
};
MeasuredEePose EePoseFromMeasurement(const RigidTransform& X_BC, const RigidTransform& X_CT,
                                     const RigidTransform& X_TE);

/// The board pose in the camera predicted from an end-effector pose:
/// X_CT = inv(X_BC) * X_BE * inv(X_TE).
RigidTransform PredictedBoardPose(const RigidTransform& X_BC, const EePose& x,
                                  const RigidTransform& X_TE);

}  // namespace h4::host

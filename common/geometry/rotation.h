// Rotations in SO(3): roll-pitch-yaw (common/README.md: R = Rz(rz) Ry(ry) Rx(rx)),
// unit quaternions, the exponential and logarithm maps, and angle wrapping.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace h4 {

/// Wraps an angle (rad) to (-pi, pi]. Every difference of joint angles is wrapped
/// (common/README.md: the H4's readings sit near +-pi).
double WrapAngle(double angle);

/// R = Rz(rpy[2]) * Ry(rpy[1]) * Rx(rpy[0]) (fixed-axis roll, pitch, yaw), rad.
Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy);

/// Inverse of RotationFromRpy: roll, pitch in [-pi/2, pi/2], yaw, rad. At pitch = +-pi/2
/// (gimbal lock) roll is set to 0 and yaw takes the whole angle.
Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R);

/// Rotation about z by angle (rad).
Eigen::Matrix3d RotZ(double angle);

/// Exponential map: rotation vector w (axis * angle, rad) to rotation matrix (Rodrigues).
Eigen::Matrix3d So3Exp(const Eigen::Vector3d& w);

/// Logarithm map: rotation matrix to rotation vector with angle in [0, pi].
Eigen::Vector3d So3Log(const Eigen::Matrix3d& R);

/// Skew-symmetric matrix [w]x with [w]x v = w x v.
Eigen::Matrix3d Skew(const Eigen::Vector3d& w);

/// Rotation matrix from a quaternion given as (w, x, y, z); the quaternion must have
/// unit norm within `tolerance` (it is then normalised). Returns false otherwise.
bool RotationFromQuaternion(double w, double x, double y, double z, Eigen::Matrix3d* R,
                            double tolerance = 1e-3);

/// Unit quaternion of R with w >= 0 (a canonical sign), as (w, x, y, z).
Eigen::Vector4d QuaternionWxyzFromRotation(const Eigen::Matrix3d& R);

}  // namespace h4

// Rigid transforms in monogram notation (Drake): X_AB is the pose of frame B in
// frame A, so p_A = X_AB * p_B and X_AC = X_AB * X_BC.
#pragma once

#include <Eigen/Core>

namespace h4 {

class RigidTransform {
 public:
  /// The identity.
  RigidTransform() : R_(Eigen::Matrix3d::Identity()), p_(Eigen::Vector3d::Zero()) {}
  /// From a rotation matrix R_AB (assumed orthonormal) and translation p_AB (m).
  RigidTransform(const Eigen::Matrix3d& R_AB, const Eigen::Vector3d& p_AB) : R_(R_AB), p_(p_AB) {}

  /// From translation (m) and roll-pitch-yaw (rad), R = Rz Ry Rx (common/README.md).
  static RigidTransform FromTranslationRpy(const Eigen::Vector3d& translation,
                                           const Eigen::Vector3d& rpy);
  /// From translation (m) and unit quaternion (w, x, y, z).
  static RigidTransform FromTranslationQuaternion(const Eigen::Vector3d& translation,
                                                  const Eigen::Vector4d& wxyz);

  const Eigen::Matrix3d& rotation() const { return R_; }
  const Eigen::Vector3d& translation() const { return p_; }
  /// Roll-pitch-yaw of the rotation, rad.
  Eigen::Vector3d rpy() const;
  /// Unit quaternion (w, x, y, z), w >= 0.
  Eigen::Vector4d quaternion_wxyz() const;
  /// 4x4 homogeneous matrix.
  Eigen::Matrix4d matrix() const;

  /// X_BA from X_AB.
  RigidTransform inverse() const { return {R_.transpose(), -(R_.transpose() * p_)}; }

  /// X_AC = X_AB * X_BC.
  RigidTransform operator*(const RigidTransform& X_BC) const {
    return {R_ * X_BC.R_, R_ * X_BC.p_ + p_};
  }
  /// p_AQ = X_AB * p_BQ.
  Eigen::Vector3d operator*(const Eigen::Vector3d& p_BQ) const { return R_ * p_BQ + p_; }

  /// True when rotation and translation agree within the given tolerances (rad, m).
  bool IsNearlyEqualTo(const RigidTransform& other, double translation_tolerance,
                       double rotation_tolerance) const;

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d p_;
};

/// The 6-vector error of `predicted` against `measured`: (rotation vector of
/// R_measured^T R_predicted, p_predicted - p_measured) in rad and m, the residual
/// log(X_measured^-1 * X_predicted) of common/README.md's measurement-space cost
/// (translation part expressed in the parent frame).
Eigen::Matrix<double, 6, 1> PoseError(const RigidTransform& measured,
                                      const RigidTransform& predicted);

}  // namespace h4

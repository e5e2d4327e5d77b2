// Rigid transforms; see rigid_transform.h.
#include "common/geometry/rigid_transform.h"

#include "common/geometry/rotation.h"

namespace h4 {

RigidTransform RigidTransform::FromTranslationRpy(const Eigen::Vector3d& translation,
                                                  const Eigen::Vector3d& rpy) {
  return {RotationFromRpy(rpy), translation};
}

RigidTransform RigidTransform::FromTranslationQuaternion(const Eigen::Vector3d& translation,
                                                         const Eigen::Vector4d& wxyz) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized();
  return {q.toRotationMatrix(), translation};
}

Eigen::Vector3d RigidTransform::rpy() const { return RpyFromRotation(R_); }

Eigen::Vector4d RigidTransform::quaternion_wxyz() const { return QuaternionWxyzFromRotation(R_); }

Eigen::Matrix4d RigidTransform::matrix() const {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M.topLeftCorner<3, 3>() = R_;
  M.topRightCorner<3, 1>() = p_;
  return M;
}

bool RigidTransform::IsNearlyEqualTo(const RigidTransform& other, double translation_tolerance,
                                     double rotation_tolerance) const {
  return (p_ - other.p_).norm() <= translation_tolerance &&
         So3Log(R_.transpose() * other.R_).norm() <= rotation_tolerance;
}

Eigen::Matrix<double, 6, 1> PoseError(const RigidTransform& measured,
                                      const RigidTransform& predicted) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = So3Log(measured.rotation().transpose() * predicted.rotation());
  e.tail<3>() = predicted.translation() - measured.translation();
  return e;
}

}  // namespace h4

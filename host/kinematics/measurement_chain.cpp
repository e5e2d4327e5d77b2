// The measurement chain of eq. (6); see measurement_chain.h.
#include "host/kinematics/measurement_chain.h"

#include <cmath>

#include "common/geometry/rotation.h"

namespace h4::host {

RigidTransform TransformFromEePose(const EePose& x) {
  return RigidTransform(RotZ(x[3]), x.head<3>());
}

EePose EePoseFromTransform(const RigidTransform& X_BE, Eigen::Vector3d* tilt) {
  const Eigen::Matrix3d& R_BE = X_BE.rotation();
  const double theta = std::atan2(R_BE(1, 0), R_BE(0, 0));
  if (tilt != nullptr) *tilt = So3Log(RotZ(theta).transpose() * R_BE);
  const Eigen::Vector3d& p_BE = X_BE.translation();
  return EePose(p_BE.x(), p_BE.y(), p_BE.z(), theta);
}

MeasuredEePose EePoseFromMeasurement(const RigidTransform& X_BC, const RigidTransform& X_CT,
                                     const RigidTransform& X_TE) {
  MeasuredEePose measured;
  measured.x = EePoseFromTransform(X_BC * X_CT * X_TE, &measured.tilt);
  measured.tilt_angle = measured.tilt.norm();
  return measured;
}

RigidTransform PredictedBoardPose(const RigidTransform& X_BC, const EePose& x,
                                  const RigidTransform& X_TE) {
  return X_BC.inverse() * TransformFromEePose(x) * X_TE.inverse();
}

}  // namespace h4::host

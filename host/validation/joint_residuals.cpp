// Table 3 residuals and the positioning error (see joint_residuals.h).
#include "host/validation/joint_residuals.h"

#include <cmath>

#include "common/geometry/rotation.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {

JointResidualStats JointResidualsOf(const KinematicModel& model, const RigidTransform& X_BC,
                                    const RigidTransform& X_TE,
                                    const std::vector<DatasetRow>& rows) {
  JointResidualStats stats;
  std::array<double, 4> sum{}, sum_sq{};
  for (const DatasetRow& row : rows) {
    const MeasuredEePose measured = EePoseFromMeasurement(X_BC, row.X_CT, X_TE);
    const IkResult ik = model.InverseKinematics(measured.x);
    if (!ik.ok()) {
      stats.unreachable.push_back(row.pose_id);
      continue;
    }
    std::array<double, 4> r{};
    for (int i = 0; i < 4; ++i) {
      r[i] = WrapAngle(row.q[i] - ik.q[i]);
      sum[i] += r[i];
      sum_sq[i] += r[i] * r[i];
    }
    stats.pose_ids.push_back(row.pose_id);
    stats.residuals.push_back(r);
  }
  stats.poses = static_cast<int>(stats.residuals.size());
  if (stats.poses > 0) {
    for (int i = 0; i < 4; ++i) {
      stats.mean[i] = sum[i] / stats.poses;
      stats.rms[i] = std::sqrt(sum_sq[i] / stats.poses);
    }
  }
  return stats;
}

PositioningError PositioningErrorOf(const KinematicModel& model, const RigidTransform& X_BC,
                                    const RigidTransform& X_TE,
                                    const std::vector<DatasetRow>& rows) {
  PositioningError error;
  double sum_p = 0.0, sum_p2 = 0.0, sum_t = 0.0, sum_t2 = 0.0;
  for (const DatasetRow& row : rows) {
    const MeasuredEePose measured = EePoseFromMeasurement(X_BC, row.X_CT, X_TE);
    const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
    // Start from the measured pose: the nearest assembly to the truth.
    const FkResult fk = ForwardKinematics(model, q, measured.x);
    if (!fk.ok()) {
      error.failed.push_back(row.pose_id);
      continue;
    }
    const double dp = (fk.x.head<3>() - measured.x.head<3>()).norm();
    const double dt = std::abs(WrapAngle(fk.x[3] - measured.x[3]));
    sum_p += dp;
    sum_p2 += dp * dp;
    sum_t += dt;
    sum_t2 += dt * dt;
    ++error.poses;
  }
  if (error.poses > 0) {
    error.position_mean = sum_p / error.poses;
    error.position_rms = std::sqrt(sum_p2 / error.poses);
    error.theta_mean = sum_t / error.poses;
    error.theta_rms = std::sqrt(sum_t2 / error.poses);
  }
  return error;
}

}  // namespace h4::host

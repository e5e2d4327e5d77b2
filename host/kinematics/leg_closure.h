// The derivatives both models' closure equations share. Each writes leg i's closure as
// f_i = |c_i|^2 - forearm_i^2 (Model 12, eq. (1): c_i = PA_i - arm u_i; Model 31, eq. (4):
// c_i = arm_i V_i + W_i), where c_i moves with the nacelle joint A_i one-for-one, and
// A_i = A_i0 + (X + s_i h (cos theta - 1), Y + s_i h sin theta, Z) (common/README.md#nacelle).
// So df_i = 2 c_i . dA_i by the pose and by h alike.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace h4::host {

/// Row `leg` of J_f_x (nothing when J_f_x is null): df_i/d(X, Y, Z) = 2 c_i and
/// df_i/dtheta = 2 c_i . dA_i/dtheta, with s = s_i (+-1), h and theta at the pose.
inline void SetClosureByPose(int leg, const Eigen::Vector3d& c, double s, double h, double theta,
                             Eigen::Matrix4d* J_f_x) {
  if (J_f_x == nullptr) return;
  const Eigen::Vector3d A_theta(-s * h * std::sin(theta), s * h * std::cos(theta), 0.0);
  J_f_x->row(leg) << 2.0 * c.x(), 2.0 * c.y(), 2.0 * c.z(), 2.0 * c.dot(A_theta);
}

/// df_i/dh = 2 c_i . dA_i/dh, with dA_i/dh = s_i (cos(theta) - 1, sin(theta), 0).
inline double ClosureByH(const Eigen::Vector3d& c, double s, double theta) {
  return 2.0 * (c.x() * s * (std::cos(theta) - 1.0) + c.y() * s * std::sin(theta));
}

}  // namespace h4::host

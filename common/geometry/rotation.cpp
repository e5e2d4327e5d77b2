// Rotations in SO(3); see rotation.h.
#include "common/geometry/rotation.h"

#include <cmath>
#include <numbers>

namespace h4 {

double WrapAngle(double angle) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::remainder(angle, kTwoPi);  // in [-pi, pi]
  if (wrapped <= -std::numbers::pi) wrapped += kTwoPi;
  return wrapped;
}

Eigen::Matrix3d RotZ(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  // R = Rz(y) Ry(p) Rx(r): R(2,0) = -sin p, R(2,1) = cos p sin r, R(2,2) = cos p cos r,
  // R(1,0) = sin y cos p, R(0,0) = cos y cos p.
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  if (std::hypot(R(0, 0), R(1, 0)) < 1e-12) {
    // Gimbal lock: only yaw - roll (pitch = +pi/2) or yaw + roll (pitch = -pi/2) is defined.
    const double yaw = std::atan2(-R(0, 1), R(1, 1));
    return {0.0, pitch, yaw};
  }
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

Eigen::Matrix3d So3Exp(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  const Eigen::Matrix3d W = Skew(w);
  if (angle < 1e-8) {
    // Second-order Taylor expansion; exact to machine precision at this size.
    return Eigen::Matrix3d::Identity() + W + 0.5 * W * W;
  }
  return Eigen::Matrix3d::Identity() + std::sin(angle) / angle * W +
         (1.0 - std::cos(angle)) / (angle * angle) * W * W;
}

Eigen::Vector3d So3Log(const Eigen::Matrix3d& R) {
  // Through the quaternion: stable at small angles and near pi alike.
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;  // angle ~ 2 s, axis v / s
  const double angle = 2.0 * std::atan2(s, q.w());
  return angle / s * v;
}

bool RotationFromQuaternion(double w, double x, double y, double z, Eigen::Matrix3d* R,
                            double tolerance) {
  const double norm = std::sqrt(w * w + x * x + y * y + z * z);
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > tolerance) return false;
  *R = Eigen::Quaterniond(w / norm, x / norm, y / norm, z / norm).toRotationMatrix();
  return true;
}

Eigen::Vector4d QuaternionWxyzFromRotation(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return {q.w(), q.x(), q.y(), q.z()};
}

}  // namespace h4

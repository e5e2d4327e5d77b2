// OpenCV's distortion model and its inverse; see camera_model.h. The model is
//   g = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   xd = x g + 2 p1 x y + p2 (r^2 + 2 x^2),  yd = y g + p1 (r^2 + 2 y^2) + 2 p2 x y
//   u = fx xd + s yd + cx,  v = fy yd + cy
#include "common/camera/camera_model.h"

#include <cmath>

#include <Eigen/LU>

namespace h4 {

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  const Eigen::VectorXd& d = intrinsics.distortion;
  const auto n = d.size();
  for (Eigen::Index i = 0; i < n && i < 8; ++i) d_[static_cast<size_t>(i)] = d[i];
  fx_ = intrinsics.K(0, 0);
  fy_ = intrinsics.K(1, 1);
  cx_ = intrinsics.K(0, 2);
  cy_ = intrinsics.K(1, 2);
  skew_ = intrinsics.K(0, 1);
  valid_ = (n == 0 || n == 4 || n == 5 || n == 8) && fx_ > 0 && fy_ > 0;
}

Eigen::Vector2d CameraModel::Distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J_xd_xn) const {
  const double k1 = d_[0], k2 = d_[1], p1 = d_[2], p2 = d_[3], k3 = d_[4], k4 = d_[5], k5 = d_[6],
               k6 = d_[7];
  const double x = xn.x(), y = xn.y();
  const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const double a = 1 + k1 * r2 + k2 * r4 + k3 * r6;
  const double b = 1 + k4 * r2 + k5 * r4 + k6 * r6;
  const double g = a / b;
  Eigen::Vector2d xd(x * g + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                     y * g + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y);
  if (J_xd_xn != nullptr) {
    const double da = k1 + 2 * k2 * r2 + 3 * k3 * r4;
    const double db = k4 + 2 * k5 * r2 + 3 * k6 * r4;
    const double dg = (da * b - a * db) / (b * b);  // dg / d(r^2)
    (*J_xd_xn)(0, 0) = g + 2 * x * x * dg + 2 * p1 * y + 6 * p2 * x;
    (*J_xd_xn)(0, 1) = 2 * x * y * dg + 2 * p1 * x + 2 * p2 * y;
    (*J_xd_xn)(1, 0) = 2 * x * y * dg + 2 * p1 * x + 2 * p2 * y;
    (*J_xd_xn)(1, 1) = g + 2 * y * y * dg + 6 * p1 * y + 2 * p2 * x;
  }
  return xd;
}

Eigen::Vector2d CameraModel::PixelFromNormalized(const Eigen::Vector2d& xn,
                                                 Eigen::Matrix2d* J_uv_xn) const {
  Eigen::Matrix2d J_xd_xn;
  const Eigen::Vector2d xd = Distort(xn, J_uv_xn != nullptr ? &J_xd_xn : nullptr);
  Eigen::Matrix2d J_uv_xd;
  J_uv_xd << fx_, skew_, 0, fy_;
  if (J_uv_xn != nullptr) *J_uv_xn = J_uv_xd * J_xd_xn;
  return J_uv_xd * xd + Eigen::Vector2d(cx_, cy_);
}

bool CameraModel::Project(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv,
                          Eigen::Matrix<double, 2, 3>* J_uv_pCQ) const {
  const double z = p_CQ.z();
  if (!(z > 0)) return false;
  const Eigen::Vector2d xn(p_CQ.x() / z, p_CQ.y() / z);
  Eigen::Matrix2d J_uv_xn;
  *uv = PixelFromNormalized(xn, J_uv_pCQ != nullptr ? &J_uv_xn : nullptr);
  if (J_uv_pCQ != nullptr) {
    Eigen::Matrix<double, 2, 3> J_xn_p;
    J_xn_p << 1 / z, 0, -xn.x() / z, 0, 1 / z, -xn.y() / z;
    *J_uv_pCQ = J_uv_xn * J_xn_p;
  }
  return true;
}

bool CameraModel::NormalizedFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* xn) const {
  // Distorted normalised target, then Gauss-Newton on Distort(xn) = xd from xn = xd.
  const double yd = (uv.y() - cy_) / fy_;
  const double xd = (uv.x() - cx_ - skew_ * yd) / fx_;
  const Eigen::Vector2d target(xd, yd);
  Eigen::Vector2d x = target;
  for (int it = 0; it < 50; ++it) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d r = Distort(x, &J) - target;
    if (r.norm() < 1e-13) break;
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-12)) break;
    x -= J.inverse() * r;
    if (!x.allFinite()) {
      *xn = target;
      return false;
    }
  }
  *xn = x;
  return (Distort(x) - target).norm() < 1e-10;
}

bool CameraModel::IdealFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* ideal) const {
  Eigen::Vector2d xn;
  const bool ok = NormalizedFromPixel(uv, &xn);
  *ideal = Eigen::Vector2d(fx_ * xn.x() + skew_ * xn.y() + cx_, fy_ * xn.y() + cy_);
  return ok;
}

}  // namespace h4

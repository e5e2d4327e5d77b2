// The camera model's distortions and their inverses; see camera_model.h.
//
// Radial-tangential (OpenCV's cv::projectPoints):
//   g = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   xd = x g + 2 p1 x y + p2 (r^2 + 2 x^2),  yd = y g + p1 (r^2 + 2 y^2) + 2 p2 x y
// Equidistant (OpenCV's cv::fisheye::projectPoints):
//   r = |(x, y)|, theta = atan(r), theta_d = theta (1 + k1 theta^2 + ... + k4 theta^8)
//   (xd, yd) = (theta_d / r) (x, y)
// Both: u = fx xd + s yd + cx,  v = fy yd + cy.
#include "common/camera/camera_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>
#include <fmt/format.h>

namespace h4 {
namespace {

constexpr double kHalfPi = 1.5707963267948966;
constexpr double kPi = 3.141592653589793;

}  // namespace

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  const Eigen::VectorXd& d = intrinsics.distortion;
  const auto n = d.size();
  for (Eigen::Index i = 0; i < n && i < 8; ++i) d_[static_cast<size_t>(i)] = d[i];
  fx_ = intrinsics.K(0, 0);
  fy_ = intrinsics.K(1, 1);
  cx_ = intrinsics.K(0, 2);
  cy_ = intrinsics.K(1, 2);
  skew_ = intrinsics.K(0, 1);
  valid_ = IsSupportedDistortionCount(intrinsics.distortion_model, n) && fx_ > 0 && fy_ > 0;
  if (intrinsics.distortion_model == DistortionModel::kEquidistant) {
    const auto slope = [this](double theta) {
      double dthetad_dtheta = 0;
      EquidistantThetaD(theta, &dthetad_dtheta);
      return dthetad_dtheta;
    };
    max_theta_ = FirstFold(slope, kHalfPi);
    max_theta_d_ = EquidistantThetaD(max_theta_);
    max_ray_theta_ = FirstFold(slope, kPi);
    max_ray_theta_d_ = EquidistantThetaD(max_ray_theta_);
  } else {
    max_theta_ =
        FirstFold([this](double theta) { return RadTanRadialSlope(std::tan(theta)); }, kHalfPi);
    max_ray_theta_ = max_theta_;
  }
  max_r_ = max_theta_ < kHalfPi ? std::tan(max_theta_) : std::numeric_limits<double>::infinity();
}

std::string CameraModel::FoldInsideImage() const {
  if (!valid_) return "";
  // The distorted normalised radius where the radial map folds (none: one to one).
  double fold_theta = 0;
  double fold_radius = 0;
  if (intrinsics_.distortion_model == DistortionModel::kEquidistant) {
    if (!(max_ray_theta_ < kPi)) return "";
    fold_theta = max_ray_theta_;
    fold_radius = max_ray_theta_d_;
  } else {
    if (!(max_theta_ < kHalfPi)) return "";
    fold_theta = max_theta_;
    const double r = max_r_;
    const double r2 = r * r, r4 = r2 * r2, r6 = r4 * r2;
    const double a = 1 + d_[0] * r2 + d_[1] * r4 + d_[4] * r6;
    const double b = 1 + d_[5] * r2 + d_[6] * r4 + d_[7] * r6;
    fold_radius = r * a / b;
  }
  // The image's farthest pixel from any point inside it is one of its corners.
  double farthest = 0;
  double farthest_px = 0;
  const double w = intrinsics_.width - 1.0, h = intrinsics_.height - 1.0;
  for (const Eigen::Vector2d& uv : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                    Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)}) {
    const double yd = (uv.y() - cy_) / fy_;
    const double xd = (uv.x() - cx_ - skew_ * yd) / fx_;
    farthest = std::max(farthest, std::hypot(xd, yd));
    farthest_px = std::max(farthest_px, std::hypot(uv.x() - cx_, uv.y() - cy_));
  }
  if (std::isfinite(fold_radius) && farthest < fold_radius) return "";
  const double fold_px = fold_radius * 0.5 * (fx_ + fy_);
  return fmt::format(
      "the lens model folds about {:.0f} px from the principal point ({:.1f} deg off the axis) "
      "but the image reaches {:.0f} px: beyond the fold the distortion sends rays back toward "
      "the centre, so part of the image has no ray and undistortion returns a wrong one",
      fold_px, fold_theta * 180.0 / kPi, farthest_px);
}

bool CameraModel::InValidField(const Eigen::Vector3d& p_CQ) const {
  const double z = p_CQ.z();
  if (!(z > 0)) return false;
  // |(x, y)| / z < tan(max angle), written without the division.
  return p_CQ.head<2>().norm() < max_r_ * z;
}

bool CameraModel::ProjectVisible(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv) const {
  return InValidField(p_CQ) && Project(p_CQ, uv);
}

Eigen::Vector2d CameraModel::Distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J_xd_xn) const {
  return intrinsics_.distortion_model == DistortionModel::kEquidistant
             ? DistortEquidistant(xn, J_xd_xn)
             : DistortRadTan(xn, J_xd_xn);
}

Eigen::Vector2d CameraModel::DistortRadTan(const Eigen::Vector2d& xn,
                                           Eigen::Matrix2d* J_xd_xn) const {
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

double CameraModel::EquidistantThetaD(double theta, double* dthetad_dtheta) const {
  const double k1 = d_[0], k2 = d_[1], k3 = d_[2], k4 = d_[3];
  const double t2 = theta * theta, t4 = t2 * t2, t6 = t4 * t2, t8 = t4 * t4;
  if (dthetad_dtheta != nullptr) {
    *dthetad_dtheta = 1 + 3 * k1 * t2 + 5 * k2 * t4 + 7 * k3 * t6 + 9 * k4 * t8;
  }
  return theta * (1 + k1 * t2 + k2 * t4 + k3 * t6 + k4 * t8);
}

// r_d = r g(r^2) with g = a / b: d r_d / d r = g + 2 r^2 dg/d(r^2). The tangential terms
// are left out: they are small and do not fold the image. A denominator b at or below 0 is a
// pole of the rational model: the field ends there too.
double CameraModel::RadTanRadialSlope(double r) const {
  const double k1 = d_[0], k2 = d_[1], k3 = d_[4], k4 = d_[5], k5 = d_[6], k6 = d_[7];
  const double r2 = r * r, r4 = r2 * r2, r6 = r4 * r2;
  const double a = 1 + k1 * r2 + k2 * r4 + k3 * r6;
  const double b = 1 + k4 * r2 + k5 * r4 + k6 * r6;
  if (!(b > 0)) return 0;
  const double da = k1 + 2 * k2 * r2 + 3 * k3 * r4;
  const double db = k4 + 2 * k5 * r2 + 3 * k6 * r4;
  const double slope = a / b + 2 * r2 * (da * b - a * db) / (b * b);
  return std::isfinite(slope) ? slope : 0;
}

// The first angle in (0, limit] where slope(theta) is no longer positive (limit when it stays
// positive): past it two rays share a pixel and the model cannot be inverted. Scanned
// finely (a polynomial of degree 8 turns at most 4 times) then bisected. Runs once per
// model, in the constructor.
template <class Slope>
double CameraModel::FirstFold(const Slope& slope, double limit) {
  const int steps = 2048;
  for (int i = 1; i <= steps; ++i) {
    double hi = limit * i / steps;
    if (slope(hi) > 0) continue;
    double lo = limit * (i - 1) / steps;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (slope(mid) > 0 ? lo : hi) = mid;
    }
    return lo;
  }
  return limit;
}

Eigen::Vector2d CameraModel::DistortEquidistant(const Eigen::Vector2d& xn,
                                                Eigen::Matrix2d* J_xd_xn) const {
  const double r = xn.norm();
  if (r < 1e-12) {  // theta_d / r -> 1 and the second-order term vanishes at the axis
    if (J_xd_xn != nullptr) J_xd_xn->setIdentity();
    return xn;
  }
  const double theta = std::atan(r);
  double dthetad_dtheta = 0;
  const double theta_d = EquidistantThetaD(theta, &dthetad_dtheta);
  const double scale = theta_d / r;
  if (J_xd_xn != nullptr) {
    // xd = scale(r) xn: J = scale I + (dscale/dr / r) xn xn^T, with
    // dscale/dr = (dthetad/dtheta dtheta/dr - scale) / r and dtheta/dr = 1 / (1 + r^2).
    const double dscale_dr_over_r = (dthetad_dtheta / (1 + r * r) - scale) / (r * r);
    *J_xd_xn = scale * Eigen::Matrix2d::Identity() + dscale_dr_over_r * xn * xn.transpose();
  }
  return scale * xn;
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

// u = fx xd + s yd + cx, v = fy yd + cy: the focal lengths scale xd, yd; the principal point
// shifts; a distortion coefficient moves (xd, yd) by d xd / d k (the formulas at the top)
// mapped through [fx s; 0 fy].
bool CameraModel::IntrinsicJacobian(const Eigen::Vector3d& p_CQ,
                                    Eigen::MatrixXd* J_uv_intrinsics) const {
  const double z = p_CQ.z();
  if (!(z > 0)) return false;
  const Eigen::Vector2d xn(p_CQ.x() / z, p_CQ.y() / z);
  const Eigen::Vector2d xd = Distort(xn);
  const int n = intrinsic_count();
  Eigen::MatrixXd& J = *J_uv_intrinsics;
  J.setZero(2, n);
  J(0, 0) = xd.x();
  J(1, 1) = xd.y();
  J(0, 2) = 1;
  J(1, 3) = 1;
  if (n == 4) return true;
  Eigen::Matrix<double, 2, 8> J_xd_d = Eigen::Matrix<double, 2, 8>::Zero();
  const double x = xn.x(), y = xn.y();
  if (intrinsics_.distortion_model == DistortionModel::kEquidistant) {
    const double r = xn.norm();
    if (r > 1e-12) {
      const double theta = std::atan(r);
      double power = theta * theta * theta;  // theta^3, theta^5, ...
      for (int i = 0; i < 4; ++i, power *= theta * theta) J_xd_d.col(i) = (power / r) * xn;
    }
  } else {
    const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
    const double a = 1 + d_[0] * r2 + d_[1] * r4 + d_[4] * r6;
    const double b = 1 + d_[5] * r2 + d_[6] * r4 + d_[7] * r6;
    const Eigen::Vector2d dg_x = xn / b;  // d(xd, yd) / d a
    J_xd_d.col(0) = r2 * dg_x;
    J_xd_d.col(1) = r4 * dg_x;
    J_xd_d.col(2) = Eigen::Vector2d(2 * x * y, r2 + 2 * y * y);
    J_xd_d.col(3) = Eigen::Vector2d(r2 + 2 * x * x, 2 * x * y);
    J_xd_d.col(4) = r6 * dg_x;
    const Eigen::Vector2d dg_b = -xn * a / (b * b);  // d(xd, yd) / d b
    J_xd_d.col(5) = r2 * dg_b;
    J_xd_d.col(6) = r4 * dg_b;
    J_xd_d.col(7) = r6 * dg_b;
  }
  Eigen::Matrix2d J_uv_xd;
  J_uv_xd << fx_, skew_, 0, fy_;
  J.rightCols(n - 4) = J_uv_xd * J_xd_d.leftCols(n - 4);
  return true;
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
  const double yd = (uv.y() - cy_) / fy_;
  const double xd = (uv.x() - cx_ - skew_ * yd) / fx_;
  return intrinsics_.distortion_model == DistortionModel::kEquidistant
             ? UndistortEquidistant(Eigen::Vector2d(xd, yd), xn)
             : UndistortRadTan(Eigen::Vector2d(xd, yd), xn);
}

bool CameraModel::UndistortRadTan(const Eigen::Vector2d& target, Eigen::Vector2d* xn) const {
  // Gauss-Newton on Distort(xn) = xd from xn = xd.
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

bool CameraModel::UndistortEquidistant(const Eigen::Vector2d& xd, Eigen::Vector2d* xn) const {
  const double theta_d = xd.norm();
  if (theta_d < 1e-12) {
    *xn = xd;
    return true;
  }
  double theta = 0;
  if (!(theta_d < max_theta_d_) || !EquidistantTheta(theta_d, max_theta_, &theta) ||
      !(theta < kHalfPi)) {
    *xn = xd;
    return false;
  }
  *xn = xd * (std::tan(theta) / theta_d);
  return true;
}

// theta_d(theta) increases on [0, max_theta]: one root, kept bracketed; Newton steps that
// leave the bracket become bisections.
bool CameraModel::EquidistantTheta(double theta_d, double max_theta, double* theta) const {
  double lo = 0, hi = max_theta, t = std::min(theta_d, max_theta);
  for (int it = 0; it < 100; ++it) {
    double slope = 0;
    const double residual = EquidistantThetaD(t, &slope) - theta_d;
    if (std::abs(residual) < 1e-15) break;
    (residual > 0 ? hi : lo) = t;
    const double newton = t - residual / slope;
    t = (slope > 0 && newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
  }
  *theta = t;
  return std::abs(EquidistantThetaD(t) - theta_d) < 1e-10;
}

bool CameraModel::ProjectRay(const Eigen::Vector3d& p_CQ, Eigen::Vector2d* uv) const {
  if (intrinsics_.distortion_model != DistortionModel::kEquidistant) {
    return ProjectVisible(p_CQ, uv);
  }
  const double rho = p_CQ.head<2>().norm();
  if (!(rho > 0 || p_CQ.z() > 0)) return false;  // the centre, or straight behind
  const double theta = std::atan2(rho, p_CQ.z());
  if (!(theta < max_ray_theta_)) return false;
  // The equidistant map written with the angle, not x/z, so that it holds past 90 degrees.
  const double scale =
      rho > 1e-12 * std::abs(p_CQ.z()) ? EquidistantThetaD(theta) / rho : 1.0 / p_CQ.z();
  const double xd = p_CQ.x() * scale, yd = p_CQ.y() * scale;
  *uv = Eigen::Vector2d(fx_ * xd + skew_ * yd + cx_, fy_ * yd + cy_);
  return true;
}

bool CameraModel::RayFromPixel(const Eigen::Vector2d& uv, Eigen::Vector3d* ray_C) const {
  const double yd = (uv.y() - cy_) / fy_;
  const double xd = (uv.x() - cx_ - skew_ * yd) / fx_;
  if (intrinsics_.distortion_model != DistortionModel::kEquidistant) {
    Eigen::Vector2d xn;
    if (!UndistortRadTan(Eigen::Vector2d(xd, yd), &xn)) return false;
    *ray_C = Eigen::Vector3d(xn.x(), xn.y(), 1.0).normalized();
    return true;
  }
  const double theta_d = std::hypot(xd, yd);
  if (theta_d < 1e-12) {
    *ray_C = Eigen::Vector3d(0, 0, 1);
    return true;
  }
  double theta = 0;
  if (!(theta_d < max_ray_theta_d_) || !EquidistantTheta(theta_d, max_ray_theta_, &theta)) {
    return false;
  }
  const double s = std::sin(theta) / theta_d;
  *ray_C = Eigen::Vector3d(xd * s, yd * s, std::cos(theta));
  return true;
}

bool CameraModel::IdealFromPixel(const Eigen::Vector2d& uv, Eigen::Vector2d* ideal) const {
  Eigen::Vector2d xn;
  const bool ok = NormalizedFromPixel(uv, &xn);
  *ideal = Eigen::Vector2d(fx_ * xn.x() + skew_ * xn.y() + cx_, fy_ * xn.y() + cy_);
  return ok;
}

}  // namespace h4

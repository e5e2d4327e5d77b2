// Planar PnP with distortion; see pose_estimator.h.
#include "firmware/pose/pose_estimator.h"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "common/geometry/rotation.h"

namespace h4::cam {
namespace {

struct Refined {
  RigidTransform X_CT;
  double cost = std::numeric_limits<double>::infinity();  // sum of squared residuals
  int iterations = 0;
};

// Levenberg-Marquardt on the reprojection error with the analytic Jacobian.
Refined RefineLm(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                 RigidTransform X, const PoseOptions& options) {
  Refined out;
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!ReprojectionResiduals(corners, camera, X, &r, &J)) return out;
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    const Eigen::Matrix<double, 6, 6> JtJ = J.transpose() * J;
    const Eigen::Matrix<double, 6, 1> g = J.transpose() * r;
    bool accepted = false;
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    while (lambda < 1e10) {
      Eigen::Matrix<double, 6, 6> A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12);
      delta = A.ldlt().solve(-g);
      if (!delta.allFinite()) break;
      const RigidTransform candidate(X.rotation() * So3Exp(delta.tail<3>()),
                                     X.translation() + delta.head<3>());
      Eigen::VectorXd r_new;
      if (ReprojectionResiduals(corners, camera, candidate, &r_new) &&
          r_new.squaredNorm() <= cost) {
        X = candidate;
        cost = r_new.squaredNorm();
        lambda = std::max(lambda * 0.1, 1e-12);
        accepted = true;
        break;
      }
      lambda *= 10;
    }
    if (!accepted) break;
    ReprojectionResiduals(corners, camera, X, &r, &J);
    if (delta.norm() < options.step_tolerance) break;
  }
  out.X_CT = X;
  out.cost = cost;
  out.iterations = it;
  return out;
}

}  // namespace

bool ReprojectionResiduals(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                           const RigidTransform& X_CT, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  const auto n = static_cast<Eigen::Index>(corners.size());
  r->resize(2 * n);
  if (J != nullptr) J->resize(2 * n, 6);
  const Eigen::Matrix3d& R_CT = X_CT.rotation();
  for (Eigen::Index i = 0; i < n; ++i) {
    const CornerObservation& c = corners[static_cast<size_t>(i)];
    const Eigen::Vector3d p_CQ = X_CT * c.p_TQ;
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J_uv_p;
    if (!camera.Project(p_CQ, &uv, J != nullptr ? &J_uv_p : nullptr)) return false;
    r->segment<2>(2 * i) = uv - c.uv;
    if (J != nullptr) {
      // p_CQ = R_CT Exp(dr) p_TQ + p_CT + dt: d/d(dt) = I, d/d(dr) = -R_CT [p_TQ]x.
      J->block<2, 3>(2 * i, 0) = J_uv_p;
      J->block<2, 3>(2 * i, 3) = -J_uv_p * R_CT * Skew(c.p_TQ);
    }
  }
  return true;
}

PoseEstimate EstimatePose(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                          const PoseOptions& options) {
  PoseEstimate estimate;
  estimate.corners = static_cast<int>(corners.size());
  if (estimate.corners < std::max(options.min_corners, 4)) {
    estimate.status = PoseEstimate::Status::kTooFewCorners;
    estimate.message = std::to_string(estimate.corners) + " corners, need " +
                       std::to_string(std::max(options.min_corners, 4));
    return estimate;
  }
  // IPPE on undistorted normalised points (identity camera matrix, no distortion).
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const CornerObservation& c : corners) {
    Eigen::Vector2d xn;
    if (!camera.NormalizedFromPixel(c.uv, &xn)) continue;
    object.emplace_back(c.p_TQ.x(), c.p_TQ.y(), c.p_TQ.z());
    image.emplace_back(xn.x(), xn.y());
  }
  std::vector<cv::Mat> rvecs, tvecs;
  if (object.size() >= 4) {
    try {
      cv::solvePnPGeneric(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvecs, tvecs, false,
                          cv::SOLVEPNP_IPPE);
    } catch (const cv::Exception&) {
      rvecs.clear();  // degenerate configuration (collinear points): no start
    }
  }
  std::vector<Refined> solutions;
  for (size_t k = 0; k < rvecs.size(); ++k) {
    cv::Mat R_cv;
    cv::Rodrigues(rvecs[k], R_cv);
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    cv::cv2eigen(R_cv, R);
    cv::cv2eigen(tvecs[k], t);
    Refined refined = RefineLm(corners, camera, RigidTransform(R, t), options);
    if (std::isfinite(refined.cost)) solutions.push_back(refined);
  }
  if (solutions.empty()) {
    estimate.message = "no pose: IPPE found no start or every refinement failed";
    return estimate;
  }
  size_t best = 0;
  for (size_t k = 1; k < solutions.size(); ++k) {
    if (solutions[k].cost < solutions[best].cost) best = k;
  }
  const double m = 2.0 * estimate.corners;
  estimate.alternative_rms_px = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < solutions.size(); ++k) {
    if (k != best) estimate.alternative_rms_px = std::sqrt(solutions[k].cost / m);
  }
  const Refined& sol = solutions[best];
  estimate.X_CT = sol.X_CT;
  estimate.iterations = sol.iterations;
  estimate.rms_px = std::sqrt(sol.cost / m);

  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  ReprojectionResiduals(corners, camera, sol.X_CT, &r, &J);
  const Eigen::Matrix<double, 6, 6> JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(JtJ);
  if (!lu.isInvertible()) {
    estimate.message = "degenerate corner layout: the pose is not observable";
    return estimate;
  }
  const double dof = m - 6.0;
  const double sigma2 = dof > 0 ? sol.cost / dof : 0.0;
  estimate.covariance = sigma2 * lu.inverse();
  estimate.covariance = 0.5 * (estimate.covariance + estimate.covariance.transpose()).eval();
  estimate.sigma_t =
      std::sqrt(std::max(0.0, estimate.covariance.topLeftCorner<3, 3>().trace() / 3));
  estimate.sigma_r =
      std::sqrt(std::max(0.0, estimate.covariance.bottomRightCorner<3, 3>().trace() / 3));
  estimate.status = PoseEstimate::Status::kOk;
  return estimate;
}

}  // namespace h4::cam

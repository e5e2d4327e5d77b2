// The intrinsics' covariance and the board pose's sensitivity to them; see
// intrinsics_uncertainty.h. A corner p_CQ = R p_TQ + t moves by -R [p_TQ]x dw + dt for a
// body rotation dw and a translation dt; its pixel by the camera model's J_uv_pCQ.
#include "common/camera/intrinsics_uncertainty.h"

#include <algorithm>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"

namespace h4 {
namespace {

// One view's weighted residuals and their Jacobians by the intrinsics and by the pose.
struct ViewJacobians {
  Eigen::MatrixXd J_c;                         // 2k x intrinsic count
  Eigen::Matrix<double, Eigen::Dynamic, 6> J_p;  // 2k x 6
  Eigen::VectorXd r;                           // 2k, weighted
};

bool ViewJacobiansOf(const CameraModel& model, const CalibrationViewFit& view,
                     ViewJacobians* out) {
  const PoseCorners& c = view.corners;
  const Eigen::Index rows = 2 * static_cast<Eigen::Index>(c.uv.size());
  out->J_c.setZero(rows, model.intrinsic_count());
  out->J_p.setZero(rows, 6);
  out->r.setZero(rows);
  const Eigen::Matrix3d R = view.X_CT.rotation();
  Eigen::MatrixXd J_uv_c;
  for (size_t k = 0; k < c.uv.size(); ++k) {
    const double w = c.weight[k];
    if (w == 0) continue;
    const Eigen::Vector3d p_CQ = view.X_CT * c.p_TQ[k];
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J_uv_p;
    if (!model.Project(p_CQ, &uv, &J_uv_p) || !model.IntrinsicJacobian(p_CQ, &J_uv_c))
      return false;
    const Eigen::Index i = 2 * static_cast<Eigen::Index>(k);
    out->r.segment<2>(i) = w * (uv - c.uv[k]);
    out->J_p.block<2, 3>(i, 0) = -w * J_uv_p * R * Skew(c.p_TQ[k]);
    out->J_p.block<2, 3>(i, 3) = w * J_uv_p;
    out->J_c.middleRows<2>(i) = w * J_uv_c;
  }
  return true;
}

}  // namespace

std::optional<IntrinsicsCovariance> IntrinsicsCovarianceOf(
    const CameraIntrinsics& camera, const std::vector<CalibrationViewFit>& views,
    bool tie_focal_lengths, const std::vector<int>& held) {
  const CameraModel model(camera);
  const int n = model.intrinsic_count();
  // Free intrinsics -> all: with tied focal lengths one column f, fx = (fx/fy) fy; a held
  // intrinsic has no column.
  std::vector<int> free_columns;
  for (int i = tie_focal_lengths ? 1 : 0; i < n; ++i) {
    if (i < 2 || std::find(held.begin(), held.end(), i) == held.end()) free_columns.push_back(i);
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(free_columns.size()));
  for (size_t c = 0; c < free_columns.size(); ++c) {
    T(free_columns[c], static_cast<Eigen::Index>(c)) = 1.0;
  }
  if (tie_focal_lengths) T(0, 0) = camera.K(0, 0) / camera.K(1, 1);
  const Eigen::Index free = T.cols();
  Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(free, free);
  double sum_sq = 0;
  Eigen::Index residuals = 0;
  ViewJacobians v;
  for (const CalibrationViewFit& view : views) {
    if (!ViewJacobiansOf(model, view, &v)) return std::nullopt;
    const Eigen::MatrixXd J_c = v.J_c * T;
    const Eigen::Matrix<double, 6, 6> H_pp = v.J_p.transpose() * v.J_p;
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(H_pp);
    if (ldlt.info() != Eigen::Success) return std::nullopt;
    const Eigen::MatrixXd H_pc = v.J_p.transpose() * J_c;
    schur.noalias() += J_c.transpose() * J_c - H_pc.transpose() * ldlt.solve(H_pc);
    sum_sq += v.r.squaredNorm();
    residuals += (v.r.array() != 0.0).count();
  }
  const Eigen::Index parameters = free + 6 * static_cast<Eigen::Index>(views.size());
  if (residuals <= parameters) return std::nullopt;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(schur);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) return std::nullopt;
  IntrinsicsCovariance out;
  const double s2 = sum_sq / static_cast<double>(residuals - parameters);
  out.sigma_px = std::sqrt(s2);
  out.covariance = T * (s2 * ldlt.solve(Eigen::MatrixXd::Identity(free, free))) * T.transpose();
  out.covariance = (0.5 * (out.covariance + out.covariance.transpose())).eval();
  if (!out.covariance.allFinite()) return std::nullopt;
  return out;
}

std::optional<Eigen::MatrixXd> BoardPoseByIntrinsics(const CameraIntrinsics& camera,
                                                     const std::vector<Eigen::Vector3d>& p_TQ,
                                                     const RigidTransform& X_CT) {
  const CameraModel model(camera);
  CalibrationViewFit view{{}, X_CT};
  for (const Eigen::Vector3d& p : p_TQ) {
    Eigen::Vector2d uv;
    if (!model.ProjectVisible(X_CT * p, &uv)) continue;
    if (uv.x() < -0.5 || uv.y() < -0.5 || uv.x() > camera.width - 0.5 ||
        uv.y() > camera.height - 0.5)
      continue;
    view.corners.p_TQ.push_back(p);
    view.corners.uv.push_back(uv);
    view.corners.weight.push_back(1.0);
  }
  if (view.corners.uv.size() < 4) return std::nullopt;
  ViewJacobians v;
  if (!ViewJacobiansOf(model, view, &v)) return std::nullopt;
  const Eigen::Matrix<double, 6, 6> H_pp = v.J_p.transpose() * v.J_p;
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(H_pp);
  if (!lu.isInvertible()) return std::nullopt;
  const Eigen::MatrixXd D = -lu.solve(v.J_p.transpose() * v.J_c);
  if (!D.allFinite()) return std::nullopt;
  return D;
}

}  // namespace h4

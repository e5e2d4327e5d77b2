// The corner cost; see corner_cost.h. Per pose, the board-pose error e of the measurement
// cost (pose_chain.h, taken against the measured X_CT) gives dX_CT_predicted by every
// parameter: a body rotation Jr(e_r) de_r and a translation de_t in C. A corner
// p_CQ = R_CT p_TQ + p_CT then moves by -R_CT [p_TQ]x d_body + dp_CT, and its pixel by the
// camera model's J_uv_pCQ (common/camera/camera_model.h).
#include "host/identification/corner_cost.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <fmt/core.h>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "host/identification/camera_parameters.h"
#include "host/identification/pose_chain.h"

namespace h4::host {

CornerCost::CornerCost(const KinematicModel& model, std::vector<DatasetRow> rows,
                       std::vector<PoseCorners> corners, CameraIntrinsics camera)
    : model_(model.Clone()),
      rows_(std::move(rows)),
      corners_(std::move(corners)),
      camera_(std::move(camera)),
      fk_(rows_.size()) {
  Eigen::Index offset = 0;
  for (const PoseCorners& c : corners_) {
    pose_offset_.push_back(offset);
    offset += 2 * static_cast<Eigen::Index>(c.uv.size());
  }
  residual_count_ = static_cast<int>(offset);
}

CornerCost::CornerCost(const CornerCost& other)
    : model_(other.model_->Clone()),
      rows_(other.rows_),
      corners_(other.corners_),
      camera_(other.camera_),
      pose_offset_(other.pose_offset_),
      residual_count_(other.residual_count_),
      whitening_(other.whitening_),
      prior_values_(other.prior_values_),
      prior_whitening_(other.prior_whitening_),
      fk_(other.fk_) {}

void CornerCost::SetJointNoiseRatio(double ratio) {
  whitening_.clear();
  if (!(ratio > 0) || J_joints_.size() != rows_.size()) return;
  for (const Eigen::Matrix<double, Eigen::Dynamic, 4>& G : J_joints_) {
    // U = ratio G = Q R; I + U U^T = I + Q V L V^T Q^T with R R^T = V L V^T, whose inverse
    // square root is I + Q V ((1 + L)^-1/2 - 1) V^T Q^T.
    PoseWhitening w;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(ratio * G);
    const Eigen::Index k = std::min<Eigen::Index>(4, G.rows());
    w.Q = qr.householderQ() * Eigen::MatrixXd::Identity(G.rows(), k);
    w.B.setZero();
    if (k == 4) {
      const Eigen::Matrix4d R = qr.matrixQR().topRows<4>().triangularView<Eigen::Upper>();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(R * R.transpose());
      const Eigen::Vector4d shrink =
          (Eigen::Vector4d::Ones() + eigen.eigenvalues().cwiseMax(0.0)).cwiseSqrt().cwiseInverse() -
          Eigen::Vector4d::Ones();
      w.B = eigen.eigenvectors() * shrink.asDiagonal() * eigen.eigenvectors().transpose();
    }
    whitening_.push_back(std::move(w));
  }
}

bool CornerCost::SetCameraPrior(const Eigen::VectorXd& file_values,
                                const Eigen::MatrixXd& covariance) {
  prior_whitening_.resize(0, 0);
  const Eigen::Index n = file_values.size();
  if (covariance.rows() != n || covariance.cols() != n || !covariance.allFinite()) return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 *
                                                             (covariance + covariance.transpose()));
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  if (!(lambda[n - 1] > 0)) return false;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (lambda[k] > 1e-12 * lambda[n - 1]) kept.push_back(k);
  }
  prior_whitening_.resize(static_cast<Eigen::Index>(kept.size()), n);
  for (size_t row = 0; row < kept.size(); ++row) {
    const Eigen::Index k = kept[row];
    prior_whitening_.row(static_cast<Eigen::Index>(row)) =
        eigen.eigenvectors().col(k).transpose() / std::sqrt(lambda[k]);
  }
  prior_values_ = file_values;
  return true;
}

bool CornerCost::Evaluate(const ParameterVector& p, Eigen::VectorXd* r, Eigen::MatrixXd* J,
                          std::string* why) {
  p.ApplyTo(model_.get());
  const CameraModel camera(WithCameraParameters(camera_, p.camera_values()));
  const ChainTransforms chain = MakeChainTransforms(p.X_BC(), p.X_TE());
  r->resize(residual_count());
  if (J != nullptr) {
    J->setZero(residual_count(), p.size());
    J_joints_.resize(rows_.size());
  }
  for (size_t j = 0; j < rows_.size(); ++j) {
    const DatasetRow& row = rows_[j];
    const std::string pose = fmt::format("pose {}", row.pose_id);
    const FkResult fk = fk_.Solve(*model_, j, row, chain.X_BC, chain.X_TE);
    if (!fk.ok()) {
      if (why != nullptr) *why = pose + ": forward kinematics";
      return false;
    }
    const BoardPoseError err = BoardPoseErrorOf(chain, fk.x, row.X_CT, J != nullptr);
    if (J != nullptr && !BoardPoseJacobian(p, row, fk.x, err)) {
      if (why != nullptr) *why = pose + ": forward kinematics singular";
      return false;
    }
    if (!EvaluateCorners(p, camera, j, err.X_CT_predicted, r, J)) {
      if (why != nullptr) *why = pose + ": a corner falls behind the camera";
      return false;
    }
    if (!whitening_.empty()) Whiten(j, r, J);
  }
  if (prior_count() > 0) {
    r->tail(prior_count()) = prior_whitening_ * (p.camera_values() - prior_values_);
    if (J != nullptr) {
      J->block(residual_count_, p.camera_offset(), prior_count(), p.camera_count()) =
          prior_whitening_;
    }
  }
  if (!r->allFinite() || (J != nullptr && !J->allFinite())) {
    if (why != nullptr) *why = "non-finite residual or Jacobian";
    return false;
  }
  return true;
}

// dX_CT_predicted by the kinematic parameters (through FK: dx = -J_f_x^-1 J_f_xi dxi), X_BC
// and X_TE, and by the joint readings (dx = -J_f_x^-1 J_f_q dq), as a body rotation rate
// Jr(e_r) de_r and a translation in C.
bool CornerCost::BoardPoseJacobian(const ParameterVector& p, const DatasetRow& row, const EePose& x,
                                   const BoardPoseError& err) {
  const int n_kin = p.kinematic_count();
  const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
  Eigen::Matrix4d J_f_x;
  Eigen::Vector4d J_f_q;
  model_->ConstraintJacobians(q, x, &J_f_x, &J_f_q, &J_f_xi_);
  const Eigen::PartialPivLU<Eigen::Matrix4d> lu(J_f_x);
  if (!(lu.rcond() > 1e-12)) return false;  // ForwardKinematicsJacobians' threshold
  J_pose_.resize(6, n_kin + 12);
  J_pose_.leftCols(n_kin) = (-err.J_e_x * lu.inverse()) * J_f_xi_;
  J_pose_.middleCols<6>(n_kin) = err.J_e_bc;
  J_pose_.middleCols<6>(n_kin + 6) = err.J_e_te;
  J_pose_q_ = (-err.J_e_x * lu.inverse()) * J_f_q.asDiagonal();
  const Eigen::Matrix3d Jr = So3RightJacobianInverse(err.e.head<3>()).inverse();
  J_pose_.topRows<3>() = (Jr * J_pose_.topRows<3>()).eval();
  J_pose_q_.topRows<3>() = (Jr * J_pose_q_.topRows<3>()).eval();
  return true;
}

// Pose j's rows times (I + Q B Q^T) (SetJointNoiseRatio).
void CornerCost::Whiten(size_t j, Eigen::VectorXd* r, Eigen::MatrixXd* J) const {
  const PoseWhitening& w = whitening_[j];
  const Eigen::Index offset = pose_offset_[j], rows = w.Q.rows();
  auto r_j = r->segment(offset, rows);
  r_j += w.Q * (w.B * (w.Q.transpose() * r_j));
  if (J == nullptr) return;
  auto J_j = J->middleRows(offset, rows);
  J_j += w.Q * (w.B * (w.Q.transpose() * J_j));
}

// A corner p_CQ = R_CT p_TQ + p_CT moves by -R_CT [p_TQ]x d_body + dp_CT.
bool CornerCost::EvaluateCorners(const ParameterVector& p, const CameraModel& camera, size_t j,
                                 const RigidTransform& X_CT, Eigen::VectorXd* r,
                                 Eigen::MatrixXd* J) {
  const PoseCorners& c = corners_[j];
  const int n_pose = p.kinematic_count() + 12;
  if (J != nullptr) J_joints_[j].setZero(2 * static_cast<Eigen::Index>(c.uv.size()), 4);
  for (size_t k = 0; k < c.uv.size(); ++k) {
    const Eigen::Vector3d p_CQ = X_CT * c.p_TQ[k];
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J_uv_p;
    if (!camera.Project(p_CQ, &uv, J != nullptr ? &J_uv_p : nullptr)) return false;
    const Eigen::Index i = pose_offset_[j] + 2 * static_cast<Eigen::Index>(k);
    const double w = c.weight[k];
    r->segment<2>(i) = w * (uv - c.uv[k]);
    if (J == nullptr || w == 0) continue;
    Eigen::Matrix<double, 2, 6> J_uv_e;
    J_uv_e.leftCols<3>() = -J_uv_p * X_CT.rotation() * Skew(c.p_TQ[k]);
    J_uv_e.rightCols<3>() = J_uv_p;
    J->block(i, 0, 2, n_pose).noalias() = w * (J_uv_e * J_pose_);
    J_joints_[j].middleRows<2>(2 * static_cast<Eigen::Index>(k)).noalias() =
        w * (J_uv_e * J_pose_q_);
    camera.IntrinsicJacobian(p_CQ, &J_uv_intrinsics_);
    J->block(i, p.camera_offset(), 2, p.camera_count()) = w * J_uv_intrinsics_;
  }
  return true;
}

}  // namespace h4::host

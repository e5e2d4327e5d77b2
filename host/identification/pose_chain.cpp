// Measurement chain of paper eq. (6) and its Jacobians; see pose_chain.h.
// Rotations are perturbed on the right (body frame): R -> R Exp(w). A pose parameter's
// rpy moves R_XY by R_XY Exp(E(rpy) d_rpy), which the chain rules below compose.
#include "host/identification/pose_chain.h"

#include <cmath>

#include "common/geometry/rotation.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {
namespace {

// d theta / d Omega for a spatial perturbation R -> Exp(Omega) R, theta = atan2(R10, R00).
Eigen::RowVector3d ThetaBySpatialRotation(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d c = R.col(0);
  const double n2 = c[0] * c[0] + c[1] * c[1];
  if (n2 < 1e-300) return Eigen::RowVector3d::Zero();
  const Eigen::RowVector3d g(-c[1] / n2, c[0] / n2, 0.0);
  return g * (-Skew(c));  // dc = Omega x c = -[c]x Omega
}

}  // namespace

Eigen::Matrix3d RpyBodyRateJacobian(const Eigen::Vector3d& rpy) {
  // R = Rz Ry Rx: dR/drx = R [ex]x, dR/dry = R [Rx^T ey]x, dR/drz = R [(Ry Rx)^T ez]x.
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()).matrix();
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()).matrix();
  Eigen::Matrix3d E;
  E.col(0) = Eigen::Vector3d::UnitX();
  E.col(1) = Rx.transpose() * Eigen::Vector3d::UnitY();
  E.col(2) = (Ry * Rx).transpose() * Eigen::Vector3d::UnitZ();
  return E;
}

Eigen::Matrix3d So3RightJacobianInverse(const Eigen::Vector3d& w) {
  const double t = w.norm();
  const Eigen::Matrix3d W = Skew(w);
  if (t < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 12.0;
  const double c = 1.0 / (t * t) - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  return Eigen::Matrix3d::Identity() + 0.5 * W + c * W * W;
}

ChainTransforms MakeChainTransforms(const RigidTransform& X_BC, const RigidTransform& X_TE) {
  return {.X_BC = X_BC,
          .X_TE = X_TE,
          .E_bc = RpyBodyRateJacobian(X_BC.rpy()),
          .E_te = RpyBodyRateJacobian(X_TE.rpy())};
}

MeasuredEePoseJacobians EePoseFromMeasurementWithJacobians(const RigidTransform& X_BC,
                                                           const RigidTransform& X_CT,
                                                           const RigidTransform& X_TE) {
  return EePoseFromMeasurementWithJacobians(MakeChainTransforms(X_BC, X_TE), X_CT);
}

MeasuredEePoseJacobians EePoseFromMeasurementWithJacobians(const ChainTransforms& chain,
                                                           const RigidTransform& X_CT) {
  const RigidTransform& X_BC = chain.X_BC;
  const RigidTransform& X_TE = chain.X_TE;
  MeasuredEePoseJacobians out;
  const RigidTransform X_BE = X_BC * X_CT * X_TE;
  const Eigen::Matrix3d& R_BE = X_BE.rotation();
  out.x.head<3>() = X_BE.translation();
  out.x[3] = std::atan2(R_BE(1, 0), R_BE(0, 0));

  const Eigen::Matrix3d& R_BC = X_BC.rotation();
  const Eigen::Matrix3d& R_CT = X_CT.rotation();
  const Eigen::Vector3d p_CE = R_CT * X_TE.translation() + X_CT.translation();
  const Eigen::RowVector3d J_theta_Omega = ThetaBySpatialRotation(R_BE);
  const Eigen::Matrix3d& E_bc = chain.E_bc;
  const Eigen::Matrix3d& E_te = chain.E_te;

  // X_BC: p_BE = R_BC p_CE + p_BC; body rate w moves p_BE by -R_BC [p_CE]x w and R_BE by
  // the spatial rate R_BC w.
  out.J_x_bc.block<3, 3>(0, 0).setIdentity();
  out.J_x_bc.block<3, 3>(0, 3) = -R_BC * Skew(p_CE) * E_bc;
  out.J_x_bc.block<1, 3>(3, 3) = J_theta_Omega * R_BC * E_bc;
  // X_TE: p_BE moves with R_BC R_CT dp_TE; R_BE -> R_BE Exp(w) is the spatial rate R_BE w.
  out.J_x_te.block<3, 3>(0, 0) = R_BC * R_CT;
  out.J_x_te.block<1, 3>(3, 3) = J_theta_Omega * R_BE * E_te;
  return out;
}

BoardPoseError BoardPoseErrorOf(const RigidTransform& X_BC, const EePose& x,
                                const RigidTransform& X_TE, const RigidTransform& X_CT_measured,
                                bool with_jacobians) {
  return BoardPoseErrorOf(MakeChainTransforms(X_BC, X_TE), x, X_CT_measured, with_jacobians);
}

BoardPoseError BoardPoseErrorOf(const ChainTransforms& chain, const EePose& x,
                                const RigidTransform& X_CT_measured, bool with_jacobians) {
  const RigidTransform& X_BC = chain.X_BC;
  const RigidTransform& X_TE = chain.X_TE;
  BoardPoseError out;
  const RigidTransform X_BE = TransformFromEePose(x);
  out.X_CT_predicted = X_BC.inverse() * X_BE * X_TE.inverse();
  out.e = PoseError(X_CT_measured, out.X_CT_predicted);
  if (!with_jacobians) return out;

  const Eigen::Matrix3d& R_BC = X_BC.rotation();
  const Eigen::Matrix3d& R_BE = X_BE.rotation();
  const Eigen::Matrix3d& R_TE = X_TE.rotation();
  const Eigen::Matrix3d& R_CT = out.X_CT_predicted.rotation();
  const Eigen::Vector3d& p_CT = out.X_CT_predicted.translation();
  const Eigen::Vector3d p_ET = -(R_TE.transpose() * X_TE.translation());
  // A body perturbation d of R_CT_predicted moves the rotation error by JrInv(e_r) d.
  const Eigen::Matrix3d Jr_inv = So3RightJacobianInverse(out.e.head<3>());
  const Eigen::Matrix3d& E_bc = chain.E_bc;
  const Eigen::Matrix3d& E_te = chain.E_te;
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();

  // End-effector pose: p_CT = R_BC^T (R_BE p_ET + p_BE - p_BC); theta turns R_BE about z.
  out.J_e_x.block<3, 3>(3, 0) = R_BC.transpose();
  out.J_e_x.block<3, 1>(0, 3) = Jr_inv * (R_TE * ez);
  out.J_e_x.block<3, 1>(3, 3) = R_BC.transpose() * R_BE * ez.cross(p_ET);
  // X_BC: R_CT -> R_CT Exp(-R_CT^T w), p_CT -> p_CT - w x p_CT.
  out.J_e_bc.block<3, 3>(3, 0) = -R_BC.transpose();
  out.J_e_bc.block<3, 3>(0, 3) = -Jr_inv * R_CT.transpose() * E_bc;
  out.J_e_bc.block<3, 3>(3, 3) = Skew(p_CT) * E_bc;
  // X_TE: R_CT -> R_CT Exp(-R_TE w); p_ET -> p_ET - w x p_ET; dp_ET/dp_TE = -R_TE^T.
  out.J_e_te.block<3, 3>(3, 0) = -R_CT;
  out.J_e_te.block<3, 3>(0, 3) = -Jr_inv * R_TE * E_te;
  out.J_e_te.block<3, 3>(3, 3) = R_BC.transpose() * R_BE * Skew(p_ET) * E_te;
  return out;
}

}  // namespace h4::host

// The measurement chain of paper eq. (6), X_BE = X_BC * X_CT * X_TE, with the analytic
// Jacobians the identification costs need: the end-effector pose (X, Y, Z, theta) from a
// measured X_CT (costs (3) and (5)), and the board-pose error of the measurement-space
// cost, log(X_CT_measured^-1 * X_CT_predicted), X_CT_predicted = inv(X_BC) X_BE inv(X_TE).
// Transforms are parameterised as (tx, ty, tz, rx, ry, rz), R = Rz Ry Rx (common/README.md).
#pragma once

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// E with dR = R [E(rpy) d_rpy]x for R = Rz Ry Rx: the body angular rates by the angles.
Eigen::Matrix3d RpyBodyRateJacobian(const Eigen::Vector3d& rpy);

/// Inverse of SO(3)'s right Jacobian at w: Log(Exp(w) Exp(d)) = w + JrInv(w) d + O(d^2).
Eigen::Matrix3d So3RightJacobianInverse(const Eigen::Vector3d& w);

/// The per-evaluation constants of the chain: X_BC, X_TE and their rpy rate Jacobians
/// (computed once per cost evaluation instead of once per pose).
struct ChainTransforms {
  RigidTransform X_BC;
  RigidTransform X_TE;
  Eigen::Matrix3d E_bc = Eigen::Matrix3d::Identity();  ///< RpyBodyRateJacobian(X_BC.rpy())
  Eigen::Matrix3d E_te = Eigen::Matrix3d::Identity();
};
ChainTransforms MakeChainTransforms(const RigidTransform& X_BC, const RigidTransform& X_TE);

/// (X, Y, Z, theta) of X_BE = X_BC X_CT X_TE with theta = atan2(R_BE[1,0], R_BE[0,0])
/// (measurement_chain.h's EePoseFromMeasurement) and its derivatives by X_BC and X_TE.
struct MeasuredEePoseJacobians {
  EePose x = EePose::Zero();
  Eigen::Matrix<double, 4, 6> J_x_bc = Eigen::Matrix<double, 4, 6>::Zero();  ///< by X_BC params
  Eigen::Matrix<double, 4, 6> J_x_te = Eigen::Matrix<double, 4, 6>::Zero();  ///< by X_TE params
};
MeasuredEePoseJacobians EePoseFromMeasurementWithJacobians(const RigidTransform& X_BC,
                                                           const RigidTransform& X_CT,
                                                           const RigidTransform& X_TE);
MeasuredEePoseJacobians EePoseFromMeasurementWithJacobians(const ChainTransforms& chain,
                                                           const RigidTransform& X_CT);

/// The 6-vector error e = PoseError(X_CT_measured, X_CT_predicted) (rotation vector, then
/// translation difference in C; rad and m) and its Jacobians.
struct BoardPoseError {
  RigidTransform X_CT_predicted;
  Eigen::Matrix<double, 6, 1> e = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 4> J_e_x = Eigen::Matrix<double, 6, 4>::Zero();   ///< by (X,Y,Z,theta)
  Eigen::Matrix<double, 6, 6> J_e_bc = Eigen::Matrix<double, 6, 6>::Zero();  ///< by X_BC params
  Eigen::Matrix<double, 6, 6> J_e_te = Eigen::Matrix<double, 6, 6>::Zero();  ///< by X_TE params
};
BoardPoseError BoardPoseErrorOf(const RigidTransform& X_BC, const EePose& x,
                                const RigidTransform& X_TE, const RigidTransform& X_CT_measured,
                                bool with_jacobians);
BoardPoseError BoardPoseErrorOf(const ChainTransforms& chain, const EePose& x,
                                const RigidTransform& X_CT_measured, bool with_jacobians);

}  // namespace h4::host

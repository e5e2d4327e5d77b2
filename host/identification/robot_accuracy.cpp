// The registered end-effector accuracy a covariance predicts; see robot_accuracy.h.
#include "host/identification/robot_accuracy.h"

#include <cmath>
#include <memory>

#include <Eigen/Cholesky>

#include "host/kinematics/forward_kinematics.h"

namespace h4::host {
namespace {

// I - P, P the projection onto the position changes a rigid motion of the base frame makes
// (translation, rotation about z), 3 rows per position.
Eigen::MatrixXd WithoutRigidMotions(const std::vector<Eigen::Vector3d>& positions) {
  const Eigen::Index n = static_cast<Eigen::Index>(positions.size());
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : positions) centre += x / static_cast<double>(n);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 4);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Vector3d d = positions[static_cast<size_t>(j)] - centre;
    R.block<3, 3>(3 * j, 0).setIdentity();
    R.block<3, 1>(3 * j, 3) = Eigen::Vector3d(-d.y(), d.x(), 0.0);
  }
  const Eigen::MatrixXd P = R * (R.transpose() * R).ldlt().solve(R.transpose());
  return Eigen::MatrixXd::Identity(3 * n, 3 * n) - P;
}

}  // namespace

std::optional<double> PredictedRobotAccuracy(const KinematicModel& model, const ParameterVector& p,
                                             const std::vector<DatasetRow>& rows,
                                             const Uncertainty& u, double board_size_sigma) {
  if (!u.ok || rows.size() < 2) return std::nullopt;
  std::unique_ptr<KinematicModel> identified = model.Clone();
  p.ApplyTo(identified.get());
  Eigen::MatrixXd J_p = Eigen::MatrixXd::Zero(3 * static_cast<Eigen::Index>(rows.size()), p.size());
  Eigen::MatrixXd J_x_xi;
  std::vector<Eigen::Vector3d> positions;
  for (size_t j = 0; j < rows.size(); ++j) {
    const JointVector q(rows[j].q[0], rows[j].q[1], rows[j].q[2], rows[j].q[3]);
    const FkResult fk = ForwardKinematics(*identified, q);
    if (!fk.ok() || !ForwardKinematicsJacobians(*identified, q, fk.x, nullptr, &J_x_xi))
      return std::nullopt;
    J_p.block(3 * static_cast<Eigen::Index>(j), 0, 3, J_x_xi.cols()) = J_x_xi.topRows<3>();
    positions.push_back(fk.x.head<3>());
  }
  const double rms = PredictedPositionAccuracy(u, WithoutRigidMotions(positions) * J_p);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : positions) centroid += x / static_cast<double>(positions.size());
  double spread2 = 0;  // mean |x - centroid|^2
  for (const Eigen::Vector3d& x : positions)
    spread2 += (x - centroid).squaredNorm() / static_cast<double>(positions.size());
  return std::sqrt(rms * rms + board_size_sigma * board_size_sigma * spread2);
}

}  // namespace h4::host

// The corner cost (common/README.md#identification-from-corners): the measurement model
// of the paper's eq. (6) carried down to the pixels the camera measured. For pose j and
// board corner Q, with X_CT_predicted = inv(X_BC) X_BE(FK(q~_j)) inv(X_TE),
//   r_jQ = (project(intrinsics, X_CT_predicted p_TQ) - uv~_jQ) / sigma_jQ      (2 per corner)
// by the kinematic parameters, X_BC, X_TE and the camera block (camera_parameters.h), so the
// intrinsics are estimated with the robot instead of being trusted. The Jacobian chains the
// measurement cost's board-pose Jacobian (pose_chain.h) with the projection's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/camera/board_pose_fit.h"
#include "common/camera/camera_intrinsics.h"
#include "common/camera/camera_model.h"
#include "host/formats/dataset_csv.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/pose_chain.h"
#include "host/identification/warm_forward_kinematics.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

class CornerCost {
 public:
  /// rows[j] pairs with corners[j]; `camera` gives the model, size and skew (its values are
  /// taken from the parameter vector's camera block at each evaluation).
  CornerCost(const KinematicModel& model, std::vector<DatasetRow> rows,
             std::vector<PoseCorners> corners, CameraIntrinsics camera);
  CornerCost(const CornerCost& other);
  CornerCost& operator=(const CornerCost&) = delete;

  const std::vector<DatasetRow>& rows() const { return rows_; }
  const std::vector<PoseCorners>& corners() const { return corners_; }
  std::vector<PoseCorners>* mutable_corners() { return &corners_; }
  int residual_count() const { return residual_count_; }
  /// First residual of pose j; pose j has 2 * corners[j].uv.size() residuals.
  Eigen::Index pose_offset(size_t j) const { return pose_offset_[j]; }

  /// Residuals at p (which must carry the camera block) and, when J is non-null, their
  /// Jacobian by every parameter. False when a pose's forward kinematics fails or a corner
  /// falls behind the camera (`why` names it). Not thread-safe (warm FK starts).
  bool Evaluate(const ParameterVector& p, Eigen::VectorXd* r, Eigen::MatrixXd* J,
                std::string* why = nullptr);

  /// Per pose j, the residuals' derivative by that pose's four joint readings (2 rows per
  /// corner, weighted like the residuals; rad^-1): how encoder noise moves the pose's
  /// corners together (joint_noise.h). Valid after an Evaluate at the same p with J.
  const std::vector<Eigen::Matrix<double, Eigen::Dynamic, 4>>& joint_jacobians() const {
    return J_joints_;
  }

 private:
  bool BoardPoseJacobian(const ParameterVector& p, const DatasetRow& row, const EePose& x,
                         const BoardPoseError& err);
  bool EvaluateCorners(const ParameterVector& p, const CameraModel& camera, size_t j,
                       const RigidTransform& X_CT, Eigen::VectorXd* r, Eigen::MatrixXd* J);

  std::unique_ptr<KinematicModel> model_;
  std::vector<DatasetRow> rows_;
  std::vector<PoseCorners> corners_;
  CameraIntrinsics camera_;
  std::vector<Eigen::Index> pose_offset_;
  int residual_count_ = 0;
  WarmForwardKinematics fk_;
  // Buffers reused across poses: FK's J_f_xi, the board pose by the kinematic and placement
  // parameters (6 x n), a corner's pixel by the intrinsics.
  Eigen::MatrixXd J_f_xi_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_pose_;
  Eigen::MatrixXd J_uv_intrinsics_;
  // The board pose by the pose's joint readings (6 x 4), and per pose the residuals by them.
  Eigen::Matrix<double, 6, 4> J_pose_q_;
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 4>> J_joints_;
};

}  // namespace h4::host

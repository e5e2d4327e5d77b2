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

  /// What the camera file knows, as residuals after the corners': W (c - c_file), W the
  /// inverse square root of the file's `intrinsics_covariance` (eigenvalues above 1e-12 of the
  /// largest), so the fit is the posterior given the file. False (no prior) when the
  /// covariance's size is not the camera block's or it has no positive eigenvalue.
  bool SetCameraPrior(const Eigen::VectorXd& file_values, const Eigen::MatrixXd& covariance);
  /// Weighs each pose's corners by their joint covariance, generalised least squares: with
  /// encoder noise sigma_q (rad) a pose's weighted residuals have covariance
  /// s2 (I + ratio^2 G_j G_j^T), ratio = sigma_q / sqrt(s2), G_j = joint_jacobians()[j] at the
  /// last Evaluate with J (frozen there), and are whitened by (I + ratio^2 G_j G_j^T)^-1/2.
  /// Corners then count for what they add to a pose the encoders blur as a whole, instead of
  /// 144 independent looks. `ratio` 0 (the default) weighs the corners independently.
  void SetJointNoiseRatio(double ratio);

  /// Rows of the camera prior (after every pose's corners); 0 without one.
  int prior_count() const { return static_cast<int>(prior_whitening_.rows()); }

  const std::vector<DatasetRow>& rows() const { return rows_; }
  const std::vector<PoseCorners>& corners() const { return corners_; }
  std::vector<PoseCorners>* mutable_corners() { return &corners_; }
  /// The corners' residuals, then the camera prior's.
  int residual_count() const { return residual_count_ + prior_count(); }
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
  void Whiten(size_t j, Eigen::VectorXd* r, Eigen::MatrixXd* J) const;
  bool EvaluateCorners(const ParameterVector& p, const CameraModel& camera, size_t j,
                       const RigidTransform& X_CT, Eigen::VectorXd* r, Eigen::MatrixXd* J);

  std::unique_ptr<KinematicModel> model_;
  std::vector<DatasetRow> rows_;
  std::vector<PoseCorners> corners_;
  CameraIntrinsics camera_;
  std::vector<Eigen::Index> pose_offset_;
  int residual_count_ = 0;  ///< the corners'
  // Per pose, the whitening I + Q_j B_j Q_j^T (SetJointNoiseRatio); empty: none.
  struct PoseWhitening {
    Eigen::Matrix<double, Eigen::Dynamic, 4> Q;
    Eigen::Matrix4d B;
  };
  std::vector<PoseWhitening> whitening_;
  Eigen::VectorXd prior_values_;
  Eigen::MatrixXd prior_whitening_;  ///< rows x camera parameters
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

// See board_pose_fit.h. A corner p_CQ = R p_TQ + t moves by -R [p_TQ]x dw + dt for a body
// rotation dw and a translation dt; its pixel by the camera model's J_uv_pCQ.
#include "common/camera/board_pose_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"

namespace h4 {

bool FitBoardPose(const PoseCorners& corners, const CameraIntrinsics& camera,
                  const RigidTransform& start, RigidTransform* X_CT,
                  Eigen::Matrix<double, 6, 6>* covariance) {
  const CameraModel model(camera);
  Eigen::Matrix3d R = start.rotation();
  Eigen::Vector3d t = start.translation();
  Eigen::Matrix<double, 6, 6> H;
  int used = 0;
  for (int iteration = 0; iteration < 30; ++iteration) {
    H.setZero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    used = 0;
    for (size_t k = 0; k < corners.uv.size(); ++k) {
      const double w = corners.weight[k];
      if (w == 0) continue;
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, 3> J_uv_p;
      if (!model.Project(R * corners.p_TQ[k] + t, &uv, &J_uv_p)) return false;
      Eigen::Matrix<double, 2, 6> Jk;
      Jk.leftCols<3>() = -w * J_uv_p * R * Skew(corners.p_TQ[k]);
      Jk.rightCols<3>() = w * J_uv_p;
      H.noalias() += Jk.transpose() * Jk;
      g.noalias() += Jk.transpose() * (w * (uv - corners.uv[k]));
      ++used;
    }
    if (used < 4) return false;
    const Eigen::Matrix<double, 6, 1> step = -H.ldlt().solve(g);
    if (!step.allFinite()) return false;
    R = R * So3Exp(step.head<3>());
    t += step.tail<3>();
    if (step.head<3>().norm() < 1e-12 && step.tail<3>().norm() < 1e-12) break;
  }
  *X_CT = RigidTransform(R, t);
  if (covariance != nullptr) *covariance = H.inverse();
  return covariance == nullptr || covariance->allFinite();
}

}  // namespace h4

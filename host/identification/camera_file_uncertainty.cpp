// The camera file's consider term; see camera_file_uncertainty.h.
#include "host/identification/camera_file_uncertainty.h"

#include "common/camera/intrinsics_uncertainty.h"
#include "host/identification/identifiability.h"

namespace h4::host {

CameraShare AddCameraFileUncertainty(const ParameterVector& p, const Eigen::MatrixXd& J_full,
                                     const IdentificationCost& cost,
                                     const std::vector<DatasetRow>& calib,
                                     const CameraFileUncertainty& camera, Uncertainty* u) {
  CameraShare share;
  if (!camera.camera.intrinsics_covariance || !u->ok || cost.kind() != CostKind::kMeasurement)
    return share;
  const Eigen::MatrixXd& C_c = *camera.camera.intrinsics_covariance;
  const Eigen::MatrixXd J = FreeColumns(J_full, p);
  const Eigen::MatrixXd A_inv = u->covariance / u->sigma2;
  // G = sum_j J_j^T W_j D_j: how the weighted normal equations' right side moves with c.
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(J.cols(), C_c.rows());
  for (size_t j = 0; j < calib.size(); ++j) {
    const std::optional<Eigen::MatrixXd> D =
        BoardPoseByIntrinsics(camera.camera, camera.board_points, calib[j].X_CT);
    if (!D) continue;
    Eigen::Matrix<double, 6, 1> w;
    w.head<3>().setConstant(cost.RotationWeight(calib[j]));
    w.tail<3>().setConstant(cost.TranslationWeight(calib[j]));
    G.noalias() += J.middleRows<6>(6 * static_cast<Eigen::Index>(j)).transpose() *
                   (w.asDiagonal() * *D);
    ++share.poses;
  }
  if (share.poses == 0) return share;
  const Eigen::MatrixXd S = A_inv * G;
  u->covariance += S * C_c * S.transpose();
  u->covariance = (0.5 * (u->covariance + u->covariance.transpose())).eval();
  u->std = u->covariance.diagonal().cwiseSqrt();
  u->ok = u->std.allFinite();
  share.added = true;
  return share;
}

}  // namespace h4::host

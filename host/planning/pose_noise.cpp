// The camera noise of a planned pose (pose_noise.h).
#include "host/planning/pose_noise.h"

#include <cmath>

#include "common/camera/board_pose_fit.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {
namespace {

// The board pose's sigmas at X_CT from its exact corners in the image, or nothing.
bool CornerFitSigma(const CameraModel& camera, const BoardModel& board, const RigidTransform& X_CT,
                    double sigma_px, PoseSigma* sigma) {
  const CameraIntrinsics& intrinsics = camera.intrinsics();
  PoseCorners corners;
  for (const Eigen::Vector3d& p_TQ : board.corners()) {
    Eigen::Vector2d uv;
    if (!camera.ProjectVisible(X_CT * p_TQ, &uv)) continue;
    if (uv.x() < 0 || uv.y() < 0 || uv.x() > intrinsics.width - 1 ||
        uv.y() > intrinsics.height - 1) {
      continue;
    }
    corners.p_TQ.push_back(p_TQ);
    corners.uv.push_back(uv);
    corners.weight.push_back(1.0 / sigma_px);
  }
  Eigen::Matrix<double, 6, 6> C;
  RigidTransform fitted;
  if (corners.p_TQ.size() < 12 || !FitBoardPose(corners, intrinsics, X_CT, &fitted, &C)) {
    return false;
  }
  // Rotation first, then translation (board_pose_fit.h), as the dataset's columns hold them.
  sigma->r = std::sqrt(C.topLeftCorner<3, 3>().trace() / 3.0);
  sigma->t = std::sqrt(C.bottomRightCorner<3, 3>().trace() / 3.0);
  return std::isfinite(sigma->r) && std::isfinite(sigma->t) && sigma->r > 0 && sigma->t > 0;
}

}  // namespace

std::vector<PoseSigma> PoseSigmasFromCorners(const RobotDescription& robot,
                                             const CameraModel& camera, const BoardModel& board,
                                             const std::vector<EePose>& poses_B, double sigma_px,
                                             const PoseSigma& fallback) {
  std::vector<PoseSigma> sigmas;
  for (const EePose& x_B : poses_B) {
    PoseSigma sigma;
    const RigidTransform X_CT = PredictedBoardPose(robot.X_BC, x_B, robot.X_TE);
    sigmas.push_back(CornerFitSigma(camera, board, X_CT, sigma_px, &sigma) ? sigma : fallback);
  }
  return sigmas;
}

}  // namespace h4::host

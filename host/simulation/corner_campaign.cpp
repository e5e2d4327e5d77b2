// See corner_campaign.h.
#include "host/simulation/corner_campaign.h"

#include <random>

#include "common/camera/board_pose_fit.h"
#include "common/camera/camera_model.h"

namespace h4::host {
namespace {

// Tag id and corner number of a corner id (common/board/board_model.h), -1 for a chessboard.
int TagIdOf(const BoardModel& board, int corner_id) {
  if (!board.is_aprilgrid()) return -1;
  return std::get<AprilGridSpec>(board.spec()).first_id + corner_id / 4;
}

bool InImage(const Eigen::Vector2d& uv, const CameraIntrinsics& camera) {
  return uv.x() >= 0 && uv.y() >= 0 && uv.x() <= camera.width - 1 && uv.y() <= camera.height - 1;
}

}  // namespace

CornerCampaign SimulateCornerCampaign(const SimulatedRobot& robot, const PosePlan& plan,
                                      const BoardModel& board, const CameraIntrinsics& true_camera,
                                      const CameraIntrinsics& assumed_camera,
                                      const CornerCampaignOptions& options) {
  DatasetOptions dataset_options;
  dataset_options.noise = {.sigma_t = 0.0, .sigma_r = 0.0, .sigma_q = options.sigma_q};
  dataset_options.seed = options.seed;
  dataset_options.valid_count = options.valid_count;
  dataset_options.fill_sigma = false;
  const SimulatedDataset exact = SimulateDataset(robot, plan, dataset_options);
  const CameraModel camera(true_camera);
  std::mt19937_64 rng(options.seed ^ 0x5bd1e995u);
  std::normal_distribution<double> normal(0.0, 1.0);
  CornerCampaign out;
  for (size_t j = 0; j < exact.rows.size(); ++j) {
    DatasetRow row = exact.rows[j];
    PoseCorners pose;
    std::vector<CornerObservation> seen;
    for (int id = 0; id < board.corner_count(); ++id) {
      const Eigen::Vector3d& p_TQ = board.corners()[static_cast<size_t>(id)];
      Eigen::Vector2d uv;
      if (!camera.ProjectVisible(row.X_CT * p_TQ, &uv) || !InImage(uv, true_camera)) continue;
      uv += options.sigma_px * Eigen::Vector2d(normal(rng), normal(rng));
      seen.push_back({row.pose_id, TagIdOf(board, id), id, uv.x(), uv.y(), options.sigma_px});
      pose.p_TQ.push_back(p_TQ);
      pose.uv.push_back(uv);
      pose.weight.push_back(1.0 / options.sigma_px);
    }
    Eigen::Matrix<double, 6, 6> C;
    if (seen.size() < 12 || !FitBoardPose(pose, assumed_camera, row.X_CT, &row.X_CT, &C)) continue;
    row.sigma_r = std::sqrt(C.topLeftCorner<3, 3>().trace() / 3);
    row.sigma_t = std::sqrt(C.bottomRightCorner<3, 3>().trace() / 3);
    out.rows.push_back(row);
    out.truth.push_back(exact.truth[j]);
    out.corners.insert(out.corners.end(), seen.begin(), seen.end());
  }
  return out;
}

}  // namespace h4::host

// Simulated paired datasets; see dataset_simulator.h.
#include "host/simulation/dataset_simulator.h"

#include <algorithm>
#include <random>

#include "common/geometry/rotation.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model31.h"

namespace h4::host {

SimulatedDataset SimulateDataset(const SimulatedRobot& robot, const PosePlan& plan,
                                 const DatasetOptions& options) {
  SimulatedDataset dataset;
  const auto model = robot.MakeModel();
  const RigidTransform X_ModelB = robot.X_ModelB();
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const NoiseOptions& noise = options.noise;
  int64_t utime = options.first_utime;
  for (const PlannedPose& pose : plan) {
    const IkResult ik = model->InverseKinematics(EePoseInB31(pose.x, X_ModelB));
    if (!ik.ok()) {
      dataset.unreachable.push_back(pose.pose_id);
      continue;
    }
    SimulatedPose truth{pose.pose_id, pose.x, ik.q,
                        PredictedBoardPose(robot.X_BC, pose.x, robot.X_TE)};
    // Always draw the same count per row, so that the noise of a row does not depend on
    // the noise settings and a noise-free run pairs with a noisy one draw for draw.
    DatasetRow row;
    row.pose_id = pose.pose_id;
    row.utime = utime;
    utime += options.utime_step;
    for (int i = 0; i < 4; ++i) {
      row.q[static_cast<size_t>(i)] = WrapAngle(ik.q[i] + noise.sigma_q * normal(rng));
    }
    Eigen::Vector3d dp, dr;
    for (int k = 0; k < 3; ++k) dp[k] = noise.sigma_t * normal(rng);
    for (int k = 0; k < 3; ++k) dr[k] = noise.sigma_r * normal(rng);
    row.X_CT = RigidTransform(truth.X_CT.rotation() * So3Exp(dr), truth.X_CT.translation() + dp);
    if (options.fill_sigma) {
      row.sigma_t = noise.sigma_t;
      row.sigma_r = noise.sigma_r;
    }
    row.set = PoseSet::kCalib;
    dataset.rows.push_back(row);
    dataset.truth.push_back(truth);
  }
  // Split: a seeded Fisher-Yates draw of valid_count rows (own engine, so the split does
  // not depend on how many poses were reachable before it).
  const int n = static_cast<int>(dataset.rows.size());
  std::vector<int> order(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) order[static_cast<size_t>(k)] = k;
  std::mt19937_64 split_rng(options.seed ^ 0x9e3779b97f4a7c15ULL);
  const int valid = std::clamp(options.valid_count, 0, n);
  for (int k = 0; k < valid; ++k) {
    const int j = k + static_cast<int>(split_rng() % static_cast<uint64_t>(n - k));
    std::swap(order[static_cast<size_t>(k)], order[static_cast<size_t>(j)]);
    dataset.rows[static_cast<size_t>(order[static_cast<size_t>(k)])].set = PoseSet::kValid;
  }
  return dataset;
}

}  // namespace h4::host

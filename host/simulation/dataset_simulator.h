// Simulated paired datasets (common/formats/README.md dataset CSV rows): for each planned pose, the
// true joints from the true robot's inverse kinematics and the board pose X_CT from the true chain
// of eq. (6), X_CT = inv(X_BC) * X_BE * inv(X_TE), with seeded Gaussian noise on the encoders and
// on X_CT, and a seeded calib/valid split.
#pragma once

#include <cstdint>
#include <vector>

#include "common/units.h"
#include "host/formats/dataset_csv.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

/// One-sigma measurement noise, per axis.
struct NoiseOptions {
  double sigma_t = 0.0002;                    ///< X_CT translation, m (0.2 mm), in C
  double sigma_r = RadiansFromDegrees(0.03);  ///< X_CT rotation, rad (0.03 deg),
                                              ///< as R_CT Exp(n): in T, as PoseError measures it
  double sigma_q = 2e-5;                      ///< encoder readings, rad

  /// Exact measurements: the board poses and joints as the robot holds them.
  static NoiseOptions None() { return {.sigma_t = 0.0, .sigma_r = 0.0, .sigma_q = 0.0}; }
};

struct DatasetOptions {
  NoiseOptions noise;
  uint64_t seed = 1;     ///< noise and split; the same seed gives the same dataset
  int valid_count = 10;  ///< rows marked "valid" (the rest "calib"), chosen by seed
  int64_t first_utime = 1700000000000000;  ///< utime of the first row, us since the epoch
  int64_t utime_step = 2000000;            ///< between rows, us
  bool fill_sigma = true;  ///< fill the rows' sigma_t, sigma_r with the noise settings
};

/// The truth behind one row.
struct SimulatedPose {
  int64_t pose_id = 0;
  EePose x_B = EePose::Zero();          ///< true end-effector pose in B
  JointVector q = JointVector::Zero();  ///< true joints (noise-free)
  RigidTransform X_CT;                  ///< true board pose (noise-free)
};

struct SimulatedDataset {
  std::vector<DatasetRow> rows;      ///< noisy, in plan order, set and sigma filled
  std::vector<SimulatedPose> truth;  ///< same order as rows
  std::vector<int64_t> unreachable;  ///< planned pose ids the true robot cannot reach
};

/// Simulates the dataset of `plan` (poses in B) on `robot`. Never throws for unreachable
/// poses: they are listed and skipped. valid_count is clamped to the number of rows.
SimulatedDataset SimulateDataset(const SimulatedRobot& robot, const PosePlan& plan,
                                 const DatasetOptions& options = DatasetOptions{});

}  // namespace h4::host

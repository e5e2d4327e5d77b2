// Square-path validation (paper IV.D, last experiment): a controller drives the end-effector
// around a square with the Model 12 inverse kinematics of its parameters (a priori or
// identified); the true robot (simulation) reaches FK_true(q_commanded). The error on each
// side is how far the reached path lies from the commanded side (the paper: 5 mm before
// calibration, under 0.5 mm after).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct SquareOptions {
  double side = 0.100;                                        ///< side length, m
  Eigen::Vector3d centre = Eigen::Vector3d(0.0, 0.0, -0.45);  ///< in B, m
  double theta = 0.0;                                         ///< nacelle angle, rad
  int points_per_side = 21;                                   ///< including both corners
  /// Empty when valid, else what is wrong.
  std::string Problem() const;
};

struct SquareSideError {
  double rms = 0.0;  ///< RMS distance from the reached points to the commanded side, m
  double max = 0.0;  ///< m
  double mean_position_error = 0.0;  ///< mean |reached - commanded point|, m
  double shape_rms = 0.0;            ///< as rms, after removing the square's mean offset, m
  double shape_max = 0.0;            ///< m
};

struct SquareRun {
  std::vector<Eigen::Vector3d> commanded;  ///< target points in B, m
  std::vector<Eigen::Vector3d> reached;    ///< true positions in B, m
  std::array<SquareSideError, 4> sides{};
  double rms = 0.0;        ///< over all points, distance to the commanded side, m
  double shape_rms = 0.0;  ///< the same after removing the mean offset, m
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< mean reached - commanded, m
  double mean_position_error = 0.0;  ///< mean |reached - commanded|, m (absolute accuracy)
};

/// The true robot: its kinematic model and X_ModelB, the map from B to its base frame.
struct TrueRobotView {
  const KinematicModel* model = nullptr;
  RigidTransform X_ModelB;
};

/// Runs the square. Throws std::invalid_argument, naming the corner or point, when the
/// controller's IK or the true robot's FK cannot reach a point (e.g. a square too large).
SquareRun RunSquare(const KinematicModel& controller, const TrueRobotView& truth,
                    const SquareOptions& options);

}  // namespace h4::host

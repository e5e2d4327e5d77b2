// Square-path validation (paper IV.D, last experiment): a controller drives the end-effector
// around a square with the Model 12 inverse kinematics of its parameters (a priori or
// identified); the true robot (simulation) reaches FK_true(q_commanded), a real robot's path
// is measured by the camera (measured_square.h). The error on each side is how far the
// reached path lies from the commanded side (the paper: 5 mm before calibration, under
// 0.5 mm after). Both paths share the point generator and the error computation here.
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

/// One commanded point of the square.
struct SquarePoint {
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  ///< target position in B, m
  int side = 0;                                   ///< side it lies on, 0..3
};

/// The commanded points in path order: side 1 from corner (-,-) to (+,-) in B's X-Y plane,
/// then (+,-) to (+,+), (+,+) to (-,+), (-,+) back to (-,-); points_per_side evenly spaced
/// points per side including both corners, so each corner appears twice (end of a side,
/// start of the next): 4 * points_per_side points. Throws std::invalid_argument when the
/// options are invalid.
std::vector<SquarePoint> SquarePoints(const SquareOptions& options);

struct SquareSideError {
  double rms = 0.0;  ///< RMS distance from the reached points to the commanded side, m
  double max = 0.0;  ///< m
  double mean_position_error = 0.0;  ///< mean |reached - commanded point|, m
  double shape_rms = 0.0;            ///< as rms, after removing the square's mean offset, m
  double shape_max = 0.0;            ///< m
  int points = 0;                    ///< points on this side
};

struct SquareRun {
  std::vector<Eigen::Vector3d> commanded;  ///< target points in B, m
  std::vector<Eigen::Vector3d> reached;    ///< true (or measured) positions in B, m
  std::vector<int> side;                   ///< side (0..3) of each point
  std::vector<double> distance;            ///< each point's distance to its side's line, m
  std::array<SquareSideError, 4> sides{};
  double rms = 0.0;        ///< over all points, distance to the commanded side, m
  double shape_rms = 0.0;  ///< the same after removing the mean offset, m
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< mean reached - commanded, m
  double mean_position_error = 0.0;  ///< mean |reached - commanded|, m (absolute accuracy)
};

/// The side errors of a path: reached[k] is where the robot went when commanded[k] (both in
/// B, m), which lies on side side[k] (0..3) of the square. A side's line is the one through
/// its first and last commanded points. Throws std::invalid_argument when the sizes differ, a
/// side index is out of range, or a side has fewer than 2 distinct commanded points (naming
/// the side, 1..4).
SquareRun SquareErrorsOf(std::vector<Eigen::Vector3d> commanded,
                         std::vector<Eigen::Vector3d> reached, std::vector<int> side);

/// The true robot: its kinematic model and X_ModelB, the map from B to its base frame.
struct TrueRobotView {
  const KinematicModel* model = nullptr;
  RigidTransform X_ModelB;
};

/// The end-effector poses the true robot reaches, in B, for the square's points (X_BE).
/// Throws std::invalid_argument, naming the corner or point, when the controller's IK or
/// the true robot's FK cannot reach a point (e.g. a square too large).
std::vector<RigidTransform> ReachedSquarePoses(const KinematicModel& controller,
                                               const TrueRobotView& truth,
                                               const SquareOptions& options);

/// Runs the square: SquareErrorsOf(SquarePoints, ReachedSquarePoses). Throws as
/// ReachedSquarePoses does.
SquareRun RunSquare(const KinematicModel& controller, const TrueRobotView& truth,
                    const SquareOptions& options);

}  // namespace h4::host

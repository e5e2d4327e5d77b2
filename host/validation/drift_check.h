// Whether a robot still matches an identification result (`h4cal check`): a short
// verification campaign (a few poses) is compared with what the result predicts. Each
// pose's board pose error e (the measurement-space residual of the identification,
// identification_cost.h, in units of the measurement sigmas) is judged against its
// predicted covariance S = I + J C J^T: the measurement's own (I in those units) plus the
// result's parameter covariance C (`parameter_covariance`, common/formats/README.md)
// propagated through the pose's Jacobian J. A result written before that key gives only
// its sigmas: C is then their diagonal, which ignores the correlations and mostly widens
// what is allowed. The measurement's own part is the camera's stated covariance plus the
// result's `camera_error_floor` (f_r, f_t per axis): a camera whose stated covariance misses
// part of its error left that misfit in the calibration, and an unchanged robot's fresh
// poses show the same, so I becomes D = diag(1 + (f_r / sigma_r)^2 x3, 1 + (f_t / sigma_t)^2 x3)
// in the pose's stated sigmas.
// Under an unchanged robot d^2 = e^T S^-1 e is chi-square with 6 degrees of
// freedom per pose and their sum chi-square with 6 n; a pose is flagged above the per-pose quantile
// (Bonferroni over the poses), and the robot has drifted when a pose is flagged or the sum exceeds
// its quantile.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_model.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

struct DriftCheckOptions {
  /// Probability that an unchanged robot has some pose flagged (shared over the poses).
  double pose_false_alarm = 0.01;
  /// Probability that an unchanged robot fails the sum test.
  double total_false_alarm = 0.02;
  CostOptions cost;  ///< sigmas of rows without their own

  bool IsValid(std::string* why) const;
};

struct PoseCheck {
  int64_t pose_id = 0;
  double mahalanobis2 = 0.0;    ///< d^2, chi-square(6) under an unchanged robot
  double position_error = 0.0;  ///< |translation error| in C, m
  double rotation_error = 0.0;  ///< |rotation error|, rad
  bool flagged = false;
  /// e: measured minus predicted board pose (rotation, translation) in measurement sigmas.
  Eigen::Matrix<double, 6, 1> error = Eigen::Matrix<double, 6, 1>::Zero();
  /// S = D + J C J^T, e's covariance under an unchanged robot (measurement sigmas squared).
  Eigen::Matrix<double, 6, 6> predicted_covariance = Eigen::Matrix<double, 6, 6>::Identity();
};

struct DriftCheckResult {
  std::vector<PoseCheck> poses;
  double chi2 = 0.0;            ///< sum of d^2
  int dof = 0;                  ///< 6 per pose
  double pose_threshold = 0.0;  ///< d^2 above this flags a pose
  double total_threshold = 0.0;
  /// At most how often an unchanged robot is called DRIFT: the two tests' false alarms.
  double false_alarm = 0.0;
  bool evaluable = true;  ///< false: a pose could not be evaluated (why in message)
  bool drift = false;
  std::string message;
  bool with_correlations = true;  ///< false: C was the diagonal of the sigmas (older result)
  /// The floor D was built from; absent: none was used (older result, or asked), D = I.
  std::optional<CameraErrorFloor> camera_floor;
  /// The verdict line, and on DRIFT what to do next (measure again, then recalibrate).
  std::string Summary() const;
};

/// p: the result's parameters; parameter_covariance: n x n over p's parameters in p's
/// order, SI (zero rows for fixed ones; all zero: judge by the measurement noise alone);
/// camera_floor: the floor in D (D = I when absent). Throws std::invalid_argument on invalid
/// options, empty rows or a covariance of the wrong size.
DriftCheckResult CheckForDrift(const KinematicModel& model, const ParameterVector& p,
                               const Eigen::MatrixXd& parameter_covariance,
                               const std::vector<DatasetRow>& rows,
                               const DriftCheckOptions& options = DriftCheckOptions{},
                               const std::optional<CameraErrorFloor>& camera_floor = {});

/// `h4cal check`: rebuilds the result's model with `assembly`, and checks the rows against
/// it with its covariance (ResultCovarianceFor, identified_robot.h; zero with
/// use_parameter_uncertainty false) and its camera_error_floor (none with use_camera_floor
/// false: the camera's stated covariance as it is).
DriftCheckResult CheckResultForDrift(const IdentificationResult& result, const Assembly& assembly,
                                     const std::vector<DatasetRow>& rows,
                                     const DriftCheckOptions& options = DriftCheckOptions{},
                                     bool use_parameter_uncertainty = true,
                                     bool use_camera_floor = true);

/// The check's poses measured again from their `corners` (on `board`, `default_sigma_px` for
/// a corner without its own) through the intrinsics of a corner-path `result` (its `camera`
/// key; `file_camera` the camera file the poses were measured with): the poses its
/// kinematics were identified on were measured so, and poses measured with the file judged
/// against it flagged every pose of an unchanged robot (issue 42, defect 7: 81 of 81, chi-square
/// 12477, limit 552). Each pose as the corner path measures it (corner_identification.h
/// RefitBoardPoses); poses without enough corners go to *dropped. Throws std::invalid_argument
/// when the result has no camera key, or no pose could be measured again.
std::vector<DatasetRow> RemeasuredWithResultCamera(
    const IdentificationResult& result, const std::vector<DatasetRow>& rows,
    const std::vector<CornerObservation>& corners, const BoardModel& board,
    const CameraIntrinsics& file_camera, double default_sigma_px, std::vector<int64_t>* dropped);

/// Upper tail quantile of chi-square with an even number of degrees of freedom: the x with
/// P(X > x) = tail_probability.
double ChiSquareUpperQuantileEvenDof(int dof, double tail_probability);

}  // namespace h4::host

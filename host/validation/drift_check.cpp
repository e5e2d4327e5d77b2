// Whether a robot still matches an identification result (drift_check.h).
#include "host/validation/drift_check.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <spdlog/fmt/fmt.h>

#include "common/text/invalid_reason.h"
#include "common/units.h"
#include "host/identification/corner_checks.h"
#include "host/identification/corner_identification.h"
#include "host/identification/identified_robot.h"
#include "host/validation/corner_residual_map.h"

namespace h4::host {

bool DriftCheckOptions::IsValid(std::string* why) const {
  if (!(pose_false_alarm > 0.0 && pose_false_alarm < 0.5)) {
    return Invalid(why, "pose_false_alarm must be in (0, 0.5)");
  }
  if (!(total_false_alarm > 0.0 && total_false_alarm < 0.5)) {
    return Invalid(why, "total_false_alarm must be in (0, 0.5)");
  }
  return true;
}

namespace {

// P(X > x) for chi-square with 2m degrees of freedom: exp(-x/2) sum_{i<m} (x/2)^i / i!,
// summed in the log domain so large m and x stay finite.
double ChiSquareEvenDofTail(int dof, double x) {
  if (x <= 0.0) return 1.0;
  const double half = 0.5 * x;
  double sum = 0.0;
  double log_term = -half;  // i = 0
  for (int i = 0; i < dof / 2; ++i) {
    if (i > 0) log_term += std::log(half) - std::log(static_cast<double>(i));
    sum += std::exp(log_term);
  }
  return std::min(1.0, sum);
}

// What the measurement's share of S was, in words.
std::string CameraFloorNote(const std::optional<CameraErrorFloor>& floor) {
  if (!floor) {
    return "\n(judged against the camera's stated pose covariance alone, without a "
           "camera_error_floor: a result written before that key has none, identify again to "
           "learn it from the calibration)";
  }
  if (floor->rotation_rad == 0.0 && floor->translation_m == 0.0) return "";
  return fmt::format(
      "\n(allowing for the camera's error beyond its stated covariance, as the calibration "
      "found it: {:.4f} deg and {:.4f} mm per axis, the result's camera_error_floor)",
      DegreesFromRadians(floor->rotation_rad), floor->translation_m * 1e3);
}

// D: the measurement's covariance in the pose's stated sigmas, with the camera's error floor.
Eigen::Matrix<double, 6, 6> MeasurementCovariance(const std::optional<CameraErrorFloor>& floor,
                                                  double rotation_weight,
                                                  double translation_weight) {
  Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Ones();
  if (floor) {
    d.head<3>().array() += std::pow(floor->rotation_rad * rotation_weight, 2);
    d.tail<3>().array() += std::pow(floor->translation_m * translation_weight, 2);
  }
  return d.asDiagonal();
}

}  // namespace

double ChiSquareUpperQuantileEvenDof(int dof, double tail_probability) {
  if (dof < 2 || dof % 2 != 0) throw std::invalid_argument("chi-square: even dof >= 2 expected");
  double low = 0.0, high = static_cast<double>(dof);
  while (ChiSquareEvenDofTail(dof, high) > tail_probability) high *= 2.0;
  for (int k = 0; k < 200 && high - low > 1e-10 * high; ++k) {
    const double mid = 0.5 * (low + high);
    (ChiSquareEvenDofTail(dof, mid) > tail_probability ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

std::string DriftCheckResult::Summary() const {
  if (!evaluable) return "not evaluable: " + message;
  int flagged = 0;
  for (const PoseCheck& pose : poses) flagged += pose.flagged ? 1 : 0;
  return fmt::format(
             "{}: {} of {} poses flagged (d^2 > {:.1f}); chi-square {:.1f} for {} dof (limit "
             "{:.1f})",
             drift ? "DRIFT: the robot no longer matches the result"
                   : "the robot matches the result",
             flagged, poses.size(), pose_threshold, chi2, dof, total_threshold) +
         CameraFloorNote(camera_floor) +
         (with_correlations ? ""
                            : "\n(the result has no parameter_covariance: its sigmas were used "
                              "without their correlations, which widens what is allowed)") +
         (drift ? fmt::format("\nnext: measure the same check poses again (an unchanged robot is "
                              "called DRIFT in at most {:.0f} % of checks); DRIFT again: the "
                              "robot has changed, recalibrate (collect a campaign, identify, "
                              "export the result whose verdict is good)",
                              100 * false_alarm)
                : "");
}

DriftCheckResult CheckForDrift(const KinematicModel& model, const ParameterVector& p,
                               const Eigen::MatrixXd& parameter_covariance,
                               const std::vector<DatasetRow>& rows,
                               const DriftCheckOptions& options,
                               const std::optional<CameraErrorFloor>& camera_floor) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("drift check options: " + why);
  if (rows.empty()) throw std::invalid_argument("drift check: no pose to check");
  if (parameter_covariance.rows() != p.size() || parameter_covariance.cols() != p.size()) {
    throw std::invalid_argument(
        fmt::format("drift check: an n x n parameter covariance expected, n = {}", p.size()));
  }
  const int n = static_cast<int>(rows.size());
  DriftCheckResult result;
  result.camera_floor = camera_floor;
  result.dof = 6 * n;
  result.pose_threshold = ChiSquareUpperQuantileEvenDof(6, options.pose_false_alarm / n);
  result.total_threshold = ChiSquareUpperQuantileEvenDof(result.dof, options.total_false_alarm);
  result.false_alarm = options.pose_false_alarm + options.total_false_alarm;

  IdentificationCost cost(CostKind::kMeasurement, model, rows, options.cost);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!cost.Evaluate(p, &r, &J, &why)) {
    result.evaluable = false;
    result.drift = true;  // a pose the result cannot even predict does not match it
    result.message = why;
    return result;
  }
  for (int j = 0; j < n; ++j) {
    const Eigen::Matrix<double, 6, 1> r_j = r.segment<6>(6 * j);
    const Eigen::MatrixXd J_j = J.middleRows(6 * j, 6);
    PoseCheck check;
    check.pose_id = rows[static_cast<size_t>(j)].pose_id;
    check.error = r_j;
    const DatasetRow& row = rows[static_cast<size_t>(j)];
    check.predicted_covariance =
        MeasurementCovariance(camera_floor, cost.RotationWeight(row), cost.TranslationWeight(row)) +
        J_j * parameter_covariance * J_j.transpose();
    check.mahalanobis2 = r_j.dot(check.predicted_covariance.ldlt().solve(r_j));
    // NaN compares false with every threshold and would pass as a match: a d^2 that is not
    // a finite number means the result cannot judge this pose.
    if (!std::isfinite(check.mahalanobis2)) {
      result.evaluable = false;
      result.drift = true;
      result.message = fmt::format(
          "pose {}: d^2 is not a finite number (the result's standard deviations or "
          "covariance are too large to predict a board pose)",
          check.pose_id);
      return result;
    }
    check.rotation_error = r_j.head<3>().norm() / cost.RotationWeight(rows[static_cast<size_t>(j)]);
    check.position_error =
        r_j.tail<3>().norm() / cost.TranslationWeight(rows[static_cast<size_t>(j)]);
    check.flagged = check.mahalanobis2 > result.pose_threshold;
    result.chi2 += check.mahalanobis2;
    result.drift = result.drift || check.flagged;
    result.poses.push_back(check);
  }
  result.drift = result.drift || result.chi2 > result.total_threshold;
  return result;
}

DriftCheckResult CheckResultForDrift(const IdentificationResult& result, const Assembly& assembly,
                                     const std::vector<DatasetRow>& rows,
                                     const DriftCheckOptions& options,
                                     bool use_parameter_uncertainty, bool use_camera_floor) {
  const IdentifiedRobot robot = RebuildFromResult(result, assembly);
  const ParameterVector p(*robot.model, robot.X_BC, robot.X_TE);
  bool with_correlations = true;
  const Eigen::MatrixXd C = use_parameter_uncertainty
                                ? ResultCovarianceFor(result, p, &with_correlations)
                                : Eigen::MatrixXd::Zero(p.size(), p.size());
  const std::optional<CameraErrorFloor> camera_floor =
      use_camera_floor ? result.camera_error_floor : std::nullopt;
  DriftCheckResult check = CheckForDrift(*robot.model, p, C, rows, options, camera_floor);
  check.with_correlations = with_correlations;
  return check;
}

std::vector<DatasetRow> RemeasuredWithResultCamera(
    const IdentificationResult& result, const std::vector<DatasetRow>& rows,
    const std::vector<CornerObservation>& corners, const BoardModel& board,
    const CameraIntrinsics& file_camera, double default_sigma_px, std::vector<int64_t>* dropped) {
  if (!result.camera) {
    throw std::invalid_argument(
        "the result has no refined camera (a pose-path result): its poses were measured with the "
        "camera file, as the check's are; the corners are not needed");
  }
  const CameraIntrinsics camera = PredictingCamera(result, file_camera);
  RequireCornersInImage(rows, corners, file_camera);
  std::vector<PoseCorners> grouped = GroupCornersByRow(rows, corners, board, default_sigma_px);
  DropDegenerateCornerPoses(rows, &grouped);
  std::vector<DatasetRow> remeasured =
      RefitBoardPoses(rows, grouped, camera, CornerFitOptions{}.min_corners_per_pose, dropped);
  if (remeasured.empty()) {
    throw std::invalid_argument(
        "no pose of the check could be measured again from the corners given (none has enough "
        "corners on the board): are they the check's?");
  }
  return remeasured;
}

}  // namespace h4::host

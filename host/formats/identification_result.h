// The identification result JSON (common/formats/README.md, `h4cal identify --out`), read back by
// fk, ik, validate, report and the controller export.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/formats/pose_columns.h"
#include "common/geometry/rigid_transform.h"
#include "host/formats/result_camera.h"
#include "host/kinematics/model_kind.h"

namespace h4 {

struct ResultParameter {
  std::string name;           ///< common/README.md name: "h", "alpha1", "x2", "X_BC.tx", ...
  double value = 0.0;         ///< identified (or fixed) value, SI
  double apriori = 0.0;       ///< a priori value, SI
  std::optional<double> std;  ///< one-sigma from the covariance; empty when fixed
  bool fixed = false;         ///< status "fixed" (else "identified")
};

struct FixedParameter {
  std::string name;
  std::string reason;
};

struct CorrelatedPair {
  std::string a, b;
  double correlation = 0.0;
};

/// The judgement of a result (`verdict` key): a code a program can act on, the text a
/// technician acts on, and the figures that decided it (name -> number, SI or plain ratio).
struct ResultVerdict {
  std::string code;  ///< good | model_cannot_describe | inconsistent_with_apriori |
                     ///< not_identifiable | too_few_poses | noise_overstated
  std::string text;
  std::vector<std::pair<std::string, double>> figures;
};

/// A pose left out of the final fit, with its score (how far it is from what the fit
/// predicts, in units of its noise) and why it was rejected.
struct RejectedPose {
  int64_t pose_id = 0;
  double score = 0.0;
  std::string reason;
};

/// Who made a result, when and from what (`provenance` key).
struct ResultProvenance {
  std::string h4cal_version;
  std::string date_utc;             ///< ISO 8601, e.g. 2026-11-23T20:01:02Z
  std::vector<std::string> inputs;  ///< the input files as given on the command line
};

/// The held-out figures of k-fold cross-validation (`cross_validation` key): every pose
/// predicted by the model fitted without its fold.
struct CrossValidationFigures {
  int folds = 0;
  int poses = 0;                ///< poses predicted
  double position_rms_m = 0.0;  ///< board position, predicted vs measured
  double rotation_rms_rad = 0.0;
  double reduced_chi2 = 0.0;  ///< of the held-out residuals normalised by the covariance
};

/// `camera_error_floor`: the board pose error the calibration's residuals show beyond the
/// camera's stated covariance, one standard deviation per axis added in quadrature to each
/// pose's stated sigma_r and sigma_t (0 when the stated sigmas explain the residuals). An
/// unchanged robot's fresh poses show the same, so `h4cal check` allows for it
/// (drift_check.h).
struct CameraErrorFloor {
  double rotation_rad = 0.0;
  double translation_m = 0.0;
};

struct IdentificationResult {
  ModelKind model = ModelKind::k12;  ///< "12" or "31" in the file
  std::vector<ResultParameter> parameters;
  RigidTransform X_BC;  ///< identified camera pose in base (B for Model 12, B31 for 31)
  RigidTransform X_TE;  ///< identified end-effector pose in board frame
  std::vector<FixedParameter> fixed;
  std::array<double, 4> calib_rms_rad{};
  std::array<double, 4> valid_rms_rad{};
  std::vector<int64_t> calib_poses, valid_poses, rejected_poses;

  // Extra keys (common/formats/README.md lets a program write more): the solver's account.
  std::string estimator;                   ///< "measurement" | "joint" (eq. 3) | "implicit" (eq. 5)
  std::optional<double> condition_number;  ///< of the scaled identification Jacobian
  std::vector<CorrelatedPair> correlations;    ///< pairs with |rho| > 0.9
  std::optional<double> valid_position_rms_m;  ///< held-out board position error, m
  std::optional<double> valid_rotation_rms_rad;
  std::optional<double> predicted_position_accuracy_m;  ///< from the covariance, calib poses
  /// Where the robot goes: the one-sigma end-effector position error the covariance predicts
  /// on the calibration poses after the rigid registration of the base frame (what
  /// host/validation/true_accuracy.h measures against a known robot), m.
  std::optional<double> predicted_robot_accuracy_m;
  std::vector<std::string> log;                ///< solver stages, one line each
  std::optional<ResultVerdict> verdict;        ///< absent in older results
  std::vector<RejectedPose> rejected_details;  ///< one per rejected pose
  std::optional<ResultProvenance> provenance;
  std::optional<CrossValidationFigures> cross_validation;
  std::optional<CameraErrorFloor> camera_error_floor;  ///< absent in older results
  /// `parameter_covariance`: n x n over `parameters` in their order, SI units (m^2, m rad,
  /// rad^2), the covariance whose diagonal gives each `std` (scaled by the reduced
  /// chi-square when it exceeds 1); a fixed parameter's row and column are zero. Absent in
  /// results written before it, or when the covariance could not be computed.
  std::optional<Eigen::MatrixXd> parameter_covariance;
  /// `parameter_covariance_camera_exact`: the same covariance had the camera's intrinsics
  /// been exact: on the pose path before the camera file's share was added (`identify
  /// --camera`), on the corner path conditioned on the refined intrinsics. What the two
  /// differ by is the camera model's share (the report's accuracy map shows it). Absent when
  /// no camera uncertainty entered the covariance, and in older results.
  std::optional<Eigen::MatrixXd> parameter_covariance_camera_exact;
  /// `camera`: the intrinsics the corner path refined with the robot (result_camera.h);
  /// absent on the pose path and in older results.
  std::optional<ResultCamera> camera;

  /// The parameter by name, or nullptr.
  const ResultParameter* Find(const std::string& name) const;
};

/// Reads/writes the JSON; reading throws FormatError (file, field path such as
/// "parameters[3].value", expectation; line 0 except for a syntax error, which gives the
/// line). Required: common/formats/README.md's keys; model "12" or "31"; parameter names unique;
/// std null for a fixed parameter (a number or null otherwise, >= 0); parameter values usable by
/// the kinematics (lengths h, arm, forearm, R, arm1..4, forearm1..4 positive; angles alpha*, q0*,
/// psi*, beta* within 2 pi; every other value and the X_BC / X_TE translations within
/// kMaxRobotSize_m); every `fixed` entry names a parameter with status "fixed"; RMS values >= 0;
/// pose ids integers; `parameter_covariance`, when given, n x n for n parameters, symmetric,
/// positive semi-definite, its diagonal the square of each `std` (relative 1e-6) and zero for a
/// parameter without one; `parameter_covariance_camera_exact` only beside it, n x n,
/// symmetric, positive semi-definite, its diagonal at most `std` squared;
/// `camera_error_floor`'s rotation within 2 pi and translation within kMaxRobotSize_m, both >= 0.
/// The extra keys may be absent or null. The writer writes every key (absent optionals as null, std
/// as null for fixed parameters), shortest round-trip numbers, and throws std::invalid_argument on
/// a non-finite number (JSON has no NaN). WriteIdentificationResult reads its text back first
/// and throws std::runtime_error, writing nothing, when this reader would refuse it.
IdentificationResult ReadIdentificationResult(const std::string& path);
IdentificationResult ParseIdentificationResult(const std::string& text,
                                               const std::string& source_name);
void WriteIdentificationResult(const std::string& path, const IdentificationResult& result);
std::string FormatIdentificationResult(const IdentificationResult& result);

}  // namespace h4

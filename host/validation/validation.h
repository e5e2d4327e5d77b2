// The validation of a calibration (paper IV.D) in one place: from the a priori robot, the
// identification results (Model 12 and/or 31), the dataset, the straightness runs and, in
// simulation, the truth, it computes the analogues of the paper's Tables 3 and 4, the square
// path under the Model 12 control law (simulated with the truth, and/or measured by the
// camera on the robot), the positioning error and the 4-DoF check. Pure: the CLI reads the
// files, the report writer draws the answer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/board/board_model.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/formats/joints_csv.h"
#include "host/identification/prior_analysis.h"
#include "host/kinematics/robot_description.h"
#include "host/simulation/truth_file.h"
#include "host/validation/accuracy_map.h"
#include "host/validation/corner_residual_map.h"
#include "host/validation/joint_residuals.h"
#include "host/validation/measured_square.h"
#include "host/validation/square_path.h"
#include "host/validation/straightness.h"
#include "host/validation/true_accuracy.h"

namespace h4::host {

/// A square path driven on the robot and measured by the camera: the dataset collected with
/// the square plan (same pose ids) by a controller (its label, e.g. "a priori").
struct MeasuredSquareInput {
  std::string label;
  std::string dataset_name;  ///< for messages
  std::vector<DatasetRow> rows;
  /// The identified model whose inverse kinematics drove the robot, when one did (labels
  /// "Model 12", "Model 31"): its square is judged in that model's base frame. Empty for
  /// another controller (the a priori model), judged in the frame of the result given.
  std::optional<ModelKind> driven_by;
};

struct ValidationInputs {
  RobotDescription apriori;
  std::optional<IdentificationResult> result12;      ///< must be a Model 12 result
  std::optional<IdentificationResult> result31;      ///< must be a Model 31 result
  std::vector<DatasetRow> rows;                      ///< the paired dataset
  std::string dataset_name;                          ///< for messages
  std::vector<std::vector<JointsRow>> straightness;  ///< ruler runs (directions 1, 2, ...)
  std::optional<SimulationTruth> truth;              ///< simulation: the true robot
  SquareOptions square;                              ///< the simulated square
  std::optional<SquarePlan> square_plan;             ///< commanded points of the measured runs
  std::vector<MeasuredSquareInput> square_measured;  ///< needs square_plan and a result
  /// The corners the camera measured with the dataset's poses, on `board`, through `camera`
  /// (the camera file h4cam measured with): the report's corner residual map. All three or
  /// none.
  std::vector<CornerObservation> corners;
  std::optional<BoardModel> board;
  std::optional<CameraIntrinsics> camera;
};

/// One row of the Table 3 / Table 4 analogues: a priori, Model 12 or Model 31.
struct ModelValidation {
  std::string label;             ///< "a priori", "Model 12", "Model 31"
  JointResidualStats heldout;    ///< Table 3 on the evaluated poses (see in_sample)
  JointResidualStats all;        ///< every dataset row (histograms)
  PositioningError positioning;  ///< FK of the readings vs measured pose, evaluated
  /// The result's k-fold cross-validated (held-out) board pose error: with every pose in the
  /// fit, the only held-out accuracy there is. Empty for the a priori and older results.
  std::optional<CrossValidationFigures> cross_validation;
  std::vector<StraightnessRun> straightness;  ///< one per ruler run
  std::optional<SquareRun> square;            ///< Model 12 controllers with a truth only
  /// Identified models whose result has a parameter covariance (accuracy_map.h).
  std::optional<AccuracyMap> accuracy_map;
  /// The same map had the camera's intrinsics been exact (the result's
  /// `parameter_covariance_camera_exact`): what the two differ by is the camera model's
  /// share. Empty when the result does not say (no camera uncertainty entered it).
  std::optional<AccuracyMap> accuracy_map_camera_exact;
  /// Where this model puts the dataset's poses (forward kinematics of their joint readings,
  /// in its base frame, the accuracy map's): those in the result's fit, and the evaluated
  /// ones (heldout_ids) when they are held out (empty when in-sample). Identified models
  /// only; a pose whose forward kinematics fails is left out.
  std::vector<EePose> calibration_poses;
  std::vector<EePose> evaluated_poses;
  /// Simulation only (a truth file): where the true robot goes when driven through this
  /// identified model over the paper's 81 grid poses, base frame registered (true_accuracy.h),
  /// beside the result's own prediction. What no camera figure can show.
  std::optional<TrueAccuracy> true_accuracy;
};

struct ValidationReport {
  std::vector<ModelValidation> models;  ///< a priori first, then 12, then 31 when given
  /// Pose ids Table 3 and the positioning error are computed on: the held-out poses, or
  /// every pose when the fit held none out (then `in_sample`).
  std::vector<int64_t> heldout_ids;
  /// The poses of heldout_ids were in a result's fit: their figures are in-sample, not a
  /// validation; the held-out accuracy is then each model's cross_validation.
  bool in_sample = false;
  PositioningError apriori_all;  ///< a priori positioning error over every row
  PriorAnalysis prior;           ///< 4-DoF check (rotation axis spread)
  bool has_truth = false;        ///< a truth file was given (simulation)
  /// The a priori is Table 2's and the truth Table 2's "Identified" rows.
  bool paper_scenario = false;
  /// The measured square runs, in the order given; placement from the Model 12 result.
  std::vector<MeasuredSquareRun> measured_squares;
  /// Where the camera model misfits, from the result whose camera the corner path refined
  /// (Model 31 first), else from a pose-path result through the camera file; with corners.
  std::optional<CornerResidualMap> corner_residuals;
  std::vector<std::string> notes;  ///< what was not computed and why
  /// Straightness improvement in percent for model m (index into models) and run r.
  double StraightnessImprovementPercent(size_t m, size_t r) const;
};

/// Throws std::invalid_argument with a clear message on bad input: a result of the wrong
/// model, a result whose held-out poses are missing from the dataset, no held-out pose, a
/// square the robot cannot follow, a ruler run where forward kinematics fails, measured
/// square runs without their plan or without a Model 12 result (their placement), or with
/// a side of fewer than 2 measured points, corners without their board or camera, or
/// corners that belong to no pose of the dataset.
ValidationReport Validate(const ValidationInputs& inputs);

/// The poses Table 3 and the positioning error are on, as every output labels them:
/// "held out (10 poses not in the fit)" or "in-sample (81 poses, none held out of the fit)".
std::string EvaluatedPosesLabel(const ValidationReport& report);

/// "10-fold cross-validated (held-out) RMS over 81 poses".
std::string CrossValidatedLabel(const CrossValidationFigures& cv);

/// True when `apriori` and `truth` are the paper's Table 2 rows (a priori, "Identified").
bool IsPaperScenario(const RobotDescription& apriori, const SimulationTruth& truth);

}  // namespace h4::host

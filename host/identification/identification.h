// Kinematic identification of an H4 (paper II-III, common/README.md#identification): from a
// rough a priori robot and a paired dataset to a filled IdentificationResult. Stages:
//  1. prior analysis of the rotation axis (paper III.B) turns the a priori X_BC / X_TE so
//     that their z axes agree with the measured axis;
//  2. warm-up stages (default: the implicit cost eq. (5), which any pose can evaluate)
//     bring the parameters close enough for the IK / FK based costs;
//  3. the estimator's cost (default: measurement space; or eq. (3), or eq. (5)), each stage
//     preceded by the identifiability analysis at its start point, solved by NLopt (loose
//     tolerance) then a Levenberg-Marquardt polish; then outlier rejection and refits;
//  4. covariance, condition number, correlations, joint residuals, held-out pose error.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/identification/camera_file_uncertainty.h"
#include "host/identification/cross_validation.h"
#include "host/identification/identifiability.h"
#include "host/identification/identification_cost.h"
#include "host/identification/identification_stage.h"
#include "host/identification/least_squares.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/prior_analysis.h"
#include "host/identification/uncertainty.h"
#include "host/identification/verdict.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

struct IdentificationOptions {
  /// The final cost: kMeasurement (default, statistically efficient), kJointSpace (the
  /// paper's eq. (3)) or kImplicit (the paper's eq. (5) for Model 31).
  CostKind estimator = CostKind::kMeasurement;
  /// Costs solved before the estimator, in order. The implicit cost needs neither IK nor
  /// FK, so it converges from an a priori whose poses may be out of the model's reach.
  std::vector<CostKind> warmup_stages = {CostKind::kImplicit};
  /// Turn the a priori X_BC / X_TE onto the measured rotation axis first (paper III.B).
  bool prior_analysis = true;
  /// In the first stage, fit X_BC and X_TE alone (kinematics at the a priori) before
  /// freeing everything: a camera off by centimetres and degrees is mostly placement.
  bool placement_first = true;
  /// Every stage starts with NLopt (algorithm by name; "none": Levenberg-Marquardt alone),
  /// loose when the LM polish follows, else to tight tolerances (1e-12, at least 2000
  /// evaluations): NLopt is the engine and copes with rough starts, LM is far faster near
  /// the minimum (timings: docs/development.md#identification-speed).
  NloptOptions nlopt;
  /// The Levenberg-Marquardt polish on the column-scaled normal equations, the final stage
  /// (false: NLopt alone, `h4cal identify --no-polish`). When it does not converge, NLopt
  /// at tight tolerances then LM again.
  bool lm_polish = true;
  LmOptions lm;
  CostOptions cost;
  IdentifiabilityOptions identifiability;
  /// Parameters the user fixes at their start value (common/README.md names).
  std::vector<std::string> fixed_parameters;
  /// The camera file and board the poses were measured with, when the file has an
  /// intrinsics_covariance (`identify --camera --board`): its share enters the measurement
  /// cost's covariance and predicted accuracy (camera_file_uncertainty.h).
  std::optional<CameraFileUncertainty> camera_file;
  /// The board YAML's h4camSizeSigma (board_spec.h BoardSizeSigma): the metric reference's
  /// uncertainty, in the predicted robot accuracy and the verdict's note.
  std::optional<double> board_size_sigma;
  /// k-fold cross-validation of the fit on every pose (cross_validation.h): the held-out
  /// figures, and the residuals outliers are judged on. folds = 0: off.
  CrossValidationOptions cross_validation;
  /// Outlier rejection, at most max_outlier_rounds times (each followed by a refit) and
  /// never more than max_rejected_fraction of the poses. With cross-validation: a pose
  /// whose held-out residual, normalised by its covariance and by the median pose's excess
  /// over the noise (so that a model's misfit of every pose is not an outlier), has a
  /// chi-square (6 dof) above outlier_chi2_limit, raised by as much as the campaign's own
  /// pose-to-pose spread of the covariances calls for (outlier_limit.h: a real camera's
  /// covariances are right on average, not pose by pose) unless the pose's held-out
  /// position error is above outlier_position_factor times the median pose's (millimetres
  /// do not depend on a covariance; 5 is beyond what a clean pose of a 3-D Gaussian error
  /// reaches, 3 times the median at 1e-4); the default limit is chi-square(6)'s 1e-4
  /// upper tail, a false rejection in about one campaign of 120 at 81 poses. Without: a
  /// pose whose residual norm exceeds outlier_factor times the median pose's.
  bool reject_outliers = true;
  double outlier_chi2_limit = 27.86;
  double outlier_position_factor = 5.0;
  double outlier_factor = 3.0;
  int max_outlier_rounds = 3;
  double max_rejected_fraction = 0.2;
  /// Parameter pairs with |correlation| above this are reported.
  double correlation_threshold = 0.9;
  /// How the verdict on the result is decided (verdict.h).
  VerdictOptions verdict;
  /// Called after every solver iteration; return false to stop.
  ProgressCallback progress;

  bool IsValid(std::string* why) const;
};

struct StageSummary {
  std::string name;  ///< e.g. "implicit (placement)", "measurement"
  CostKind cost = CostKind::kImplicit;
  int poses = 0;
  std::vector<MinimizerReport> minimizers;
  std::vector<std::string> fixed;  ///< fixed during this stage, with reasons
  double rms_before = 0.0;         ///< RMS of the residuals (rad, m, or sigma units)
  double rms_after = 0.0;
  bool ok = false;        ///< converged
  bool evaluable = true;  ///< false: the cost could not be evaluated (poses out of reach)
  std::string message;
  double analysis_seconds = 0.0;  ///< identifiability analysis at the start
  double seconds = 0.0;           ///< the whole stage
};

struct IdentificationSummary {
  std::vector<StageSummary> stages;
  bool usable = false;  ///< the final stage converged and the covariance exists
  std::string message;  ///< why it is not usable, or how it ended
  double final_cost = 0.0;
  double chi2_per_dof = 0.0;
  int iterations = 0;  ///< over all stages and minimisers
  double seconds = 0.0;
  double outlier_seconds = 0.0;  ///< outlier checks (refits excluded: they are stages)
  double report_seconds = 0.0;   ///< covariance, re-check, residuals, held-out figures
  /// A human-readable account, one stage per paragraph.
  std::string FullReport() const;
};

struct IdentificationOutcome {
  IdentificationResult result;  ///< filled entirely (common/formats/README.md)
  IdentificationSummary summary;
  ParameterVector parameters;  ///< the final vector with its fixed mask
  Uncertainty uncertainty;
  PriorAnalysis prior;
  IdentifiabilityReport identifiability;        ///< of the final stage, at its start point
  Verdict verdict = Verdict::kNotIdentifiable;  ///< also in result.verdict, with its text
  CrossValidation cross_validation;             ///< of the final pose set (folds 0: not run)
};

/// Identification from an a priori: `apriori_model` (12 or 31) with X_BC / X_TE in its base
/// frame; `calib` for identification, `valid` held out (may be empty). Throws as
/// IdentifyFromStart on bad input.
IdentificationOutcome Identify(const KinematicModel& apriori_model,
                               const RigidTransform& X_BC_apriori,
                               const RigidTransform& X_TE_apriori,
                               const std::vector<DatasetRow>& calib,
                               const std::vector<DatasetRow>& valid,
                               const IdentificationOptions& options);

/// Fewer calibration poses than this cannot be identified (and 3 are the least the prior
/// analysis of the rotation axis needs).
inline constexpr size_t kMinimumCalibrationPoses = 3;

/// The same from an explicit start (e.g. a converted Model 12 result) with `apriori` only
/// reported; parameters fixed by the analysis keep the start's values. No prior analysis.
/// Throws std::invalid_argument (preconditions on the input, checked before any work):
/// fewer than kMinimumCalibrationPoses rows in `calib`, or a name in
/// options.fixed_parameters that is not one of start.names() (the message lists them).
IdentificationOutcome IdentifyFromStart(const KinematicModel& model, const ParameterVector& apriori,
                                        const ParameterVector& start,
                                        const std::vector<DatasetRow>& calib,
                                        const std::vector<DatasetRow>& valid,
                                        const IdentificationOptions& options);

/// Calibration / validation split: the `set` column when any row has one; else
/// `valid_count` rows drawn with `seed` (reported in `how`); 0 (the default): every pose
/// in the fit, the held-out figures then come from cross-validation.
struct DatasetSplit {
  std::vector<DatasetRow> calib, valid;
  std::string how;
};
DatasetSplit SplitDataset(const std::vector<DatasetRow>& rows, int valid_count = 0,
                          uint64_t seed = 1);

/// A robot's a priori model of one kind, as an identification starts from it.
struct AprioriModel {
  std::unique_ptr<KinematicModel> model;
  ParameterVector parameters;  ///< the model's values with X_BC (in B31 for Model 31), X_TE
};

/// Model 12: the robot's model12 block. Model 31: its model31 block or the nominal Model 31
/// of its Model 12, X_BC mapped to B31.
AprioriModel AprioriModelOf(const RobotDescription& robot, ModelKind kind);

/// `h4cal identify --model 12|31`: split, a priori from the robot, Identify.
IdentificationOutcome IdentifyRobot(const RobotDescription& robot, ModelKind kind,
                                    const std::vector<DatasetRow>& rows,
                                    const IdentificationOptions& options, int valid_count = 0,
                                    uint64_t seed = 1);

/// `h4cal identify --model 31 --from result12.json` (paper III.C): Model 31 starts from the
/// nominal Model 31 of the Model 12 result, and parameters it must fix keep that result's
/// values. The poses Model 12 rejected are back in the fit: Model 31 judges its own
/// outliers (Model 12 rejects what only Model 31 can describe). The Model 12 result's
/// held-out poses stay held out when it has any and the rows carry no `set`. Throws
/// std::invalid_argument (RequireModel12Result) when model12_result is not Model 12's.
IdentificationOutcome IdentifyModel31FromModel12(const RobotDescription& robot,
                                                 const IdentificationResult& model12_result,
                                                 const std::vector<DatasetRow>& rows,
                                                 const IdentificationOptions& options);

/// Both models as the demo, `collect --report-dir` and the studies run them (paper III.C):
/// Model 12 from the a priori robot, then Model 31 from its result
/// (IdentifyModel31FromModel12), whether or not Model 12 was usable: the caller judges.
struct ModelPairOutcome {
  IdentificationOutcome model12;
  IdentificationOutcome model31;
};
ModelPairOutcome IdentifyModel12Then31(const RobotDescription& robot,
                                       const std::vector<DatasetRow>& rows,
                                       const IdentificationOptions& options);

}  // namespace h4::host

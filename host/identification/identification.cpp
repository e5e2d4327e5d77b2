// The staged identification pipeline; see identification.h. IdentifyFromStart reads
// top-down: plan and run the stages (identification_stage.h), reject outliers and refit,
// summarise the solution (solution_summary.h).
#include "host/identification/identification.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/text/invalid_reason.h"
#include "common/timing/clock.h"
#include "common/units.h"
#include "host/identification/camera_error_floor.h"
#include "host/identification/identified_robot.h"
#include "host/identification/outlier_limit.h"
#include "host/identification/solution_summary.h"
#include "host/identification/verdict_inputs.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host {
namespace {

// The preconditions of IdentifyFromStart that are the caller's input, not the solver's
// outcome: calibration poses to fit, and fixed-parameter names the model has (a typo
// silently ignored would identify a parameter the user meant to keep).
void RequireIdentifiableInput(const KinematicModel& model, const ParameterVector& start,
                              const std::vector<DatasetRow>& calib,
                              const IdentificationOptions& options) {
  if (calib.size() < kMinimumCalibrationPoses) {
    throw std::invalid_argument(
        fmt::format("identification needs at least {} calibration poses, got {} (rows with set "
                    "'valid' are held out)",
                    kMinimumCalibrationPoses, calib.size()));
  }
  for (const std::string& name : options.fixed_parameters) {
    if (start.IndexOf(name) >= 0) continue;
    std::string known;
    for (const std::string& n : start.names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("cannot fix '" + name + "': not a parameter of " +
                                ModelLabel(model.kind()) + "; the parameters are: " + known);
  }
}

// What one identification carries from step to step.
struct IdentificationState {
  ParameterVector p;                             ///< the current values, with the last stage's mask
  std::vector<DatasetRow> rows;                  ///< the calibration poses still in
  std::vector<int64_t> rejected{};               ///< pose ids rejected as outliers
  std::vector<RejectedPose> rejected_details{};  ///< the same with score and reason
  FinalStageOutputs final_stage{};  ///< the estimator's analysis and solution, on `rows`
  bool final_ok = false;            ///< the last estimator stage converged
  CrossValidation cv{};             ///< of `p` on `rows` when cv_current
  bool cv_current = false;
};

// Cross-validates the current solution unless already done.
void UpdateCrossValidation(const StageContext& context, IdentificationState* state) {
  if (state->cv_current) return;
  const IdentificationOptions& options = context.options;
  state->cv = CrossValidate(
      {context.model, state->p, state->rows, options.estimator, options.cost, options.lm},
      options.cross_validation);
  state->cv_current = true;
}

void RecordStage(const StageSummary& stage, IdentificationOutcome* out) {
  out->result.log.push_back(StageLogLine(stage));
  out->summary.stages.push_back(stage);
}

// Warm-up stages, then the estimator. False (with the reason in the summary) when a stage
// cannot evaluate its cost.
bool RunPlannedStages(const StageContext& context, IdentificationState* state,
                      IdentificationOutcome* out) {
  const std::vector<PlannedStage> plan = PlanStages(context.options);
  for (size_t s = 0; s < plan.size(); ++s) {
    const bool is_final = s + 1 == plan.size();
    const StageSummary stage = RunStage(context, plan[s], state->rows, &state->p,
                                        is_final ? &state->final_stage : nullptr);
    RecordStage(stage, out);
    if (!stage.evaluable) {
      out->summary.message = "stage " + stage.name + " failed: " + stage.message;
      return false;
    }
    state->final_ok = stage.ok;
  }
  return true;
}

// The poses judged outliers (with their scores and reasons) and the poses kept.
struct OutlierCheck {
  std::vector<int64_t> outliers;
  std::vector<RejectedPose> details;
  std::vector<DatasetRow> kept;
  double limit = 0.0;
};

// Without cross-validation: the poses whose residual norm on the estimator's solution
// exceeds outlier_factor times the median's.
std::optional<OutlierCheck> CheckOutliersInSample(const IdentificationOptions& options,
                                                  const IdentificationState& state) {
  const Eigen::VectorXd& r = state.final_stage.solution.r;
  const Eigen::Index m = IdentificationCost::ResidualsPerPose(options.estimator);
  std::vector<double> norms;
  for (Eigen::Index j = 0; j + m <= r.size(); j += m) norms.push_back(r.segment(j, m).norm());
  if (norms.empty() || norms.size() != state.rows.size()) return std::nullopt;
  std::vector<double> sorted = norms;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                   sorted.end());
  OutlierCheck check;
  const double median = sorted[sorted.size() / 2];
  check.limit = options.outlier_factor * median;
  for (size_t j = 0; j < state.rows.size(); ++j) {
    const double score = median > 0 ? norms[j] / median : 0.0;
    if (norms[j] > check.limit) {
      check.outliers.push_back(state.rows[j].pose_id);
      check.details.push_back(
          {state.rows[j].pose_id, score,
           fmt::format("in-sample residual norm {:.3g} times the median pose's (limit {:.3g})",
                       score, options.outlier_factor)});
    } else {
      check.kept.push_back(state.rows[j]);
    }
  }
  return check;
}

// The median of a 6-dof chi-square: a pose's held-out chi-square over it, at the median
// pose, is how much the misfit of every pose exceeds the noise model.
constexpr double kChi2Median6Dof = 5.348;

// See CheckOutliersHeldOut: gross outliers first, borderline poses in a later round.
constexpr double kSwampingFactor = 4.0;

// Each pose's held-out score: its chi-square over the median pose's excess (at least 1), so
// that a model's misfit of every pose is not an outlier; 0 for a pose not predicted.
struct HeldOutScores {
  std::vector<double> scores;  ///< in the order of the poses
  double excess = 1.0;
  double spread = 0.0;        ///< pose-to-pose spread of the covariances (outlier_limit.h)
  double spread_limit = 0.0;  ///< outlier_chi2_limit raised for that spread
  double worst = 0.0;
  double median_position_error_m = 0.0;  ///< over the poses predicted
};

HeldOutScores ScoreHeldOut(const std::vector<HeldOutPrediction>& poses, double chi2_limit) {
  HeldOutScores s;
  std::vector<double> chi2;
  for (const HeldOutPrediction& pose : poses) {
    if (pose.ok) chi2.push_back(pose.chi2);
  }
  if (chi2.empty()) return s;
  std::nth_element(chi2.begin(), chi2.begin() + static_cast<long>(chi2.size() / 2), chi2.end());
  s.excess = std::max(1.0, chi2[chi2.size() / 2] / kChi2Median6Dof);
  std::vector<double> position_errors;
  for (const HeldOutPrediction& pose : poses) {
    s.scores.push_back(pose.ok ? pose.chi2 / s.excess : 0.0);
    s.worst = std::max(s.worst, s.scores.back());
    if (pose.ok) position_errors.push_back(pose.position_error_m);
  }
  s.spread = ScoreSpread(s.scores);
  s.spread_limit = OverdispersedLimit(chi2_limit, s.spread);
  const auto middle = position_errors.begin() + static_cast<long>(position_errors.size() / 2);
  std::nth_element(position_errors.begin(), middle, position_errors.end());
  s.median_position_error_m = *middle;
  return s;
}

// The limit of one pose: outlier_chi2_limit raised for the spread of the covariances, except
// for a pose that is also far off in millimetres (outlier_position_factor times the median
// pose's held-out position error): the allowance is for covariances that are wrong, and a
// pose's millimetres do not depend on its covariance.
double PoseLimit(const HeldOutPrediction& pose, const IdentificationOptions& options,
                 const HeldOutScores& s) {
  if (pose.position_error_m > options.outlier_position_factor * s.median_position_error_m) {
    return options.outlier_chi2_limit;
  }
  return s.spread_limit;
}

std::string HeldOutReason(const HeldOutPrediction& pose, double score,
                          const IdentificationOptions& options, const HeldOutScores& s) {
  if (!pose.ok) {
    return "the model fitted without it cannot predict it (forward kinematics fails)";
  }
  std::string limit = fmt::format("limit {:.3g}", options.outlier_chi2_limit);
  if (s.excess > 1.0)
    limit += fmt::format(", after dividing by the median pose's {:.3g}", s.excess);
  const double pose_limit = PoseLimit(pose, options, s);
  if (pose_limit > options.outlier_chi2_limit) {
    limit += fmt::format(", {:.3g} allowing for the spread of the pose covariances (s = {:.2f})",
                         pose_limit, s.spread);
  }
  const double times_median = pose.position_error_m / std::max(s.median_position_error_m, 1e-12);
  return fmt::format(
      "held-out chi-square {:.3g} (6 dof; {}): {:.3f} mm from the pose the model fitted "
      "without it predicts, {:.1f} times the median pose's",
      score, limit, pose.position_error_m * 1e3, times_median);
}

// With cross-validation: each pose's held-out score against its PoseLimit. A pose the
// fold's model cannot predict is an outlier too.
std::optional<OutlierCheck> CheckOutliersHeldOut(const IdentificationOptions& options,
                                                 const IdentificationState& state) {
  const std::vector<HeldOutPrediction>& poses = state.cv.poses;
  if (poses.size() != state.rows.size()) return std::nullopt;
  const HeldOutScores s = ScoreHeldOut(poses, options.outlier_chi2_limit);
  if (s.scores.empty()) return std::nullopt;
  // A gross outlier is among the training poses of every other fold and inflates the
  // held-out residuals of the poses near it: a round rejects the poses within a factor
  // kSwampingFactor of the worst score, the others are judged again without them.
  OutlierCheck check;
  check.limit = std::max(s.spread_limit, s.worst / kSwampingFactor);
  for (size_t j = 0; j < poses.size(); ++j) {
    const double limit = std::max(PoseLimit(poses[j], options, s), s.worst / kSwampingFactor);
    if (!poses[j].ok || s.scores[j] > limit) {
      check.outliers.push_back(state.rows[j].pose_id);
      check.details.push_back(
          {state.rows[j].pose_id, s.scores[j], HeldOutReason(poses[j], s.scores[j], options, s)});
    } else {
      check.kept.push_back(state.rows[j]);
    }
  }
  return check;
}

std::optional<OutlierCheck> CheckOutliers(const StageContext& context, IdentificationState* state,
                                          IdentificationSummary* summary) {
  const auto check_start = std::chrono::steady_clock::now();
  std::optional<OutlierCheck> check;
  if (context.options.cross_validation.folds >= 2) {
    UpdateCrossValidation(context, state);
    check = CheckOutliersHeldOut(context.options, *state);
  } else {
    check = CheckOutliersInSample(context.options, *state);
  }
  summary->outlier_seconds += SecondsSince(check_start);
  return check;
}

// Outlier rejection on the estimator's per-pose residuals, each round followed by a refit,
// at most max_outlier_rounds times and never more than max_rejected_fraction of the poses.
void RejectOutliers(const StageContext& context, size_t calib_count, IdentificationState* state,
                    IdentificationOutcome* out) {
  const IdentificationOptions& options = context.options;
  std::vector<std::string>& log = out->result.log;
  for (int round = 0; options.reject_outliers && round < options.max_outlier_rounds; ++round) {
    std::optional<OutlierCheck> check = CheckOutliers(context, state, &out->summary);
    if (!check || check->outliers.empty()) break;
    const double max_rejected = options.max_rejected_fraction * static_cast<double>(calib_count);
    if (static_cast<double>(state->rejected.size() + check->outliers.size()) > max_rejected) {
      log.push_back(
          fmt::format("outlier rejection stopped: it would reject more than {:.0f}% of "
                      "the poses",
                      100.0 * options.max_rejected_fraction));
      break;
    }
    log.push_back(fmt::format("rejected poses {} (score above {:.3g})",
                              fmt::join(check->outliers, " "), check->limit));
    state->rejected.insert(state->rejected.end(), check->outliers.begin(), check->outliers.end());
    state->rejected_details.insert(state->rejected_details.end(), check->details.begin(),
                                   check->details.end());
    state->rows = std::move(check->kept);
    StageSummary stage =
        RunStage(context, {options.estimator, false}, state->rows, &state->p, &state->final_stage);
    stage.name += " (after rejection)";
    RecordStage(stage, out);
    state->final_ok = stage.ok;
    state->cv_current = false;
  }
}

// Iterations over all stages and the final cost, into the summary.
void CountIterations(IdentificationSummary* summary) {
  for (const StageSummary& stage : summary->stages) {
    for (const MinimizerReport& m : stage.minimizers) summary->iterations += m.iterations;
  }
  if (!summary->stages.empty() && !summary->stages.back().minimizers.empty()) {
    summary->final_cost = summary->stages.back().minimizers.back().final_cost;
  }
}

// Whether the identification is usable, and why not.
void Conclude(bool final_ok, IdentificationSummary* summary, const Uncertainty& uncertainty) {
  summary->chi2_per_dof = uncertainty.chi2_per_dof;
  summary->usable = final_ok && uncertainty.ok;
  if (!summary->message.empty()) return;
  summary->message = summary->usable ? "converged"
                     : !final_ok     ? "the final stage did not converge"
                                     : "no covariance at the solution (rank-deficient Jacobian)";
}

// The held-out figures of the final pose set, into the outcome, the result and the log.
void RecordCrossValidation(const StageContext& context, IdentificationState* state,
                           IdentificationOutcome* out) {
  UpdateCrossValidation(context, state);
  const CrossValidation& cv = state->cv;
  out->cross_validation = cv;
  int predicted = 0;
  for (const HeldOutPrediction& pose : cv.poses) predicted += pose.ok ? 1 : 0;
  out->result.cross_validation = CrossValidationFigures{cv.folds, predicted, cv.position_rms_m,
                                                        cv.rotation_rms_rad, cv.reduced_chi2};
  out->result.log.push_back(fmt::format(
      "{}-fold cross-validation: held-out board pose error RMS {:.4f} mm, {:.4f} deg over {} "
      "poses, normalised chi-square / dof {:.3g}; {} folds did not converge, {:.1f} ms",
      cv.folds, cv.position_rms_m * 1e3, DegreesFromRadians(cv.rotation_rms_rad), predicted,
      cv.reduced_chi2, cv.failed_folds, cv.seconds * 1e3));
}

// What no campaign can tell (common/README.md#identification-from-corners): with rotary
// joints a board printed 0.2 % large gives a robot 0.2 % large that fits as well.
std::string BoardScaleNote(const std::optional<double>& board_size_sigma) {
  if (!board_size_sigma) {
    return " Lengths are as right as the board's stated size, which no pose can check "
           "(a uniform scale is not observable): measure the print and state its tolerance "
           "(board YAML h4camSizeSigma, with --board) to have it in the predicted accuracy.";
  }
  return fmt::format(
      " Lengths are as right as the board's stated size, which no pose can check (a uniform "
      "scale is not observable): its stated tolerance, {:.0f} ppm, is in the predicted robot "
      "accuracy.",
      1e6 * *board_size_sigma);
}

// The verdict on the solution in `state` (verdict.h), into out->result.verdict.
void JudgeSolution(const KinematicModel& model, const ParameterVector& apriori,
                   const IdentificationState& state, size_t poses_given,
                   const IdentificationOptions& options, IdentificationOutcome* out) {
  const SolutionToJudge solution{model,
                                 apriori,
                                 state.p,
                                 state.rows,
                                 static_cast<int>(poses_given),
                                 static_cast<int>(state.rejected.size()),
                                 state.final_ok,
                                 out->uncertainty,
                                 options.cost};
  out->result.verdict =
      DecideVerdict(GatherVerdictInputs(solution), options.verdict, &out->verdict);
  if (out->verdict == Verdict::kGood)
    out->result.verdict->text += BoardScaleNote(options.board_size_sigma);
  out->result.rejected_details = state.rejected_details;
  out->result.camera_error_floor = CameraErrorFloorAt(model, state.p, state.rows, options.cost);
}

}  // namespace

bool IdentificationOptions::IsValid(std::string* why) const {
  if (nlopt.algorithm == "none" && !lm_polish) {
    return Invalid(why, "identification options: no minimiser (nlopt none, no LM)");
  }
  std::string algorithm_why;
  if (!IsValidNloptAlgorithm(nlopt.algorithm, &algorithm_why)) {
    return Invalid(why, "identification options: " + algorithm_why);
  }
  if (!(nlopt.relative_cost_tolerance > 0) || !(nlopt.relative_step_tolerance > 0)) {
    return Invalid(why, "identification options: nlopt tolerances must be positive");
  }
  if (nlopt.max_evaluations <= 0) {
    return Invalid(why, "identification options: nlopt.max_evaluations must be positive");
  }
  if (lm.max_iterations <= 0) {
    return Invalid(why, "identification options: lm.max_iterations must be positive");
  }
  if (!(cost.default_sigma_t > 0) || !(cost.default_sigma_r > 0)) {
    return Invalid(why, "identification options: default sigmas must be positive");
  }
  if (!(identifiability.relative_singular_value_threshold > 0 &&
        identifiability.relative_singular_value_threshold < 1)) {
    return Invalid(why, "identification options: identifiability threshold must be in (0, 1)");
  }
  if (reject_outliers && !(outlier_factor > 1.0)) {
    return Invalid(why, "identification options: outlier_factor must exceed 1");
  }
  if (reject_outliers && !(outlier_chi2_limit > 0.0)) {
    return Invalid(why, "identification options: outlier_chi2_limit must be positive");
  }
  if (reject_outliers && !(outlier_position_factor > 1.0)) {
    return Invalid(why, "identification options: outlier_position_factor must exceed 1");
  }
  if (std::string cv_why; !cross_validation.IsValid(&cv_why)) {
    return Invalid(why, "identification options: " + cv_why);
  }
  if (!(max_rejected_fraction >= 0 && max_rejected_fraction < 1)) {
    return Invalid(why, "identification options: max_rejected_fraction must be in [0, 1)");
  }
  if (!(correlation_threshold > 0 && correlation_threshold < 1)) {
    return Invalid(why, "identification options: correlation_threshold must be in (0, 1)");
  }
  return verdict.IsValid(why);
}

IdentificationOutcome IdentifyFromStart(const KinematicModel& model, const ParameterVector& apriori,
                                        const ParameterVector& start,
                                        const std::vector<DatasetRow>& calib,
                                        const std::vector<DatasetRow>& valid,
                                        const IdentificationOptions& options) {
  RequireIdentifiableInput(model, start, calib, options);
  const auto clock_start = std::chrono::steady_clock::now();
  IdentificationOutcome out{{}, {}, start, {}, {}, {}, Verdict::kNotIdentifiable, {}};
  const std::vector<int64_t> none_rejected;
  if (std::string why; !options.IsValid(&why)) {
    out.summary.message = why;
    SummariseSolution({.model = model,
                       .apriori = apriori,
                       .p = start,
                       .calib = calib,
                       .valid = valid,
                       .rejected = none_rejected,
                       .options = options},
                      &out);
    return out;
  }
  const StageContext context{model, options, start};
  IdentificationState state{.p = start, .rows = calib};
  const size_t poses_given = calib.size() + valid.size();
  if (!RunPlannedStages(context, &state, &out)) {
    SummariseSolution({.model = model,
                       .apriori = apriori,
                       .p = state.p,
                       .calib = calib,
                       .valid = valid,
                       .rejected = none_rejected,
                       .options = options},
                      &out);
    JudgeSolution(model, apriori, state, poses_given, options, &out);
    return out;
  }
  RejectOutliers(context, calib.size(), &state, &out);
  if (options.cross_validation.folds >= 2) RecordCrossValidation(context, &state, &out);
  CountIterations(&out.summary);
  out.parameters = state.p;
  out.identifiability = state.final_stage.identifiability;
  const auto report_start = std::chrono::steady_clock::now();
  SummariseSolution({.model = model,
                     .apriori = apriori,
                     .p = state.p,
                     .calib = state.rows,
                     .valid = valid,
                     .rejected = state.rejected,
                     .options = options,
                     .at_solution = &state.final_stage.solution},
                    &out);
  out.summary.report_seconds = SecondsSince(report_start);
  Conclude(state.final_ok, &out.summary, out.uncertainty);
  JudgeSolution(model, apriori, state, poses_given, options, &out);
  out.summary.seconds = SecondsSince(clock_start);
  return out;
}

IdentificationOutcome Identify(const KinematicModel& apriori_model,
                               const RigidTransform& X_BC_apriori,
                               const RigidTransform& X_TE_apriori,
                               const std::vector<DatasetRow>& calib,
                               const std::vector<DatasetRow>& valid,
                               const IdentificationOptions& options) {
  const ParameterVector apriori(apriori_model, X_BC_apriori, X_TE_apriori);
  ParameterVector start = apriori;
  PriorAnalysis prior;
  if (options.prior_analysis) {
    prior = AnalyzeRotationAxis(calib, X_BC_apriori, X_TE_apriori);
    if (prior.ok) {
      start.set_X_BC(prior.X_BC);
      start.set_X_TE(prior.X_TE);
    }
  }
  IdentificationOutcome out =
      IdentifyFromStart(apriori_model, apriori, start, calib, valid, options);
  if (options.prior_analysis) {
    out.result.log.insert(out.result.log.begin(), "prior analysis: " + prior.message);
  }
  out.prior = prior;
  return out;
}

DatasetSplit SplitDataset(const std::vector<DatasetRow>& rows, int valid_count, uint64_t seed) {
  DatasetSplit split;
  const bool has_set =
      std::any_of(rows.begin(), rows.end(), [](const DatasetRow& r) { return r.set.has_value(); });
  if (has_set) {
    for (const DatasetRow& row : rows) {
      (row.set == PoseSet::kValid ? split.valid : split.calib).push_back(row);
    }
    split.how = "split by the dataset's set column";
    return split;
  }
  std::vector<size_t> order(rows.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  const size_t n_valid = std::min(rows.size() / 2, static_cast<size_t>(std::max(0, valid_count)));
  std::set<size_t> valid_index(order.begin(), order.begin() + static_cast<long>(n_valid));
  for (size_t i = 0; i < rows.size(); ++i) {
    (valid_index.count(i) ? split.valid : split.calib).push_back(rows[i]);
  }
  split.how = n_valid == 0
                  ? "every pose in the fit"
                  : fmt::format("{} validation poses drawn at random (seed {})", n_valid, seed);
  return split;
}

AprioriModel AprioriModelOf(const RobotDescription& robot, ModelKind kind) {
  if (kind == ModelKind::k12) {
    auto model = std::make_unique<Model12>(robot.model12, robot.assembly);
    ParameterVector parameters(*model, robot.X_BC, robot.X_TE);
    return {std::move(model), std::move(parameters)};
  }
  auto model = std::make_unique<Model31>(Model31Of(robot), robot.assembly);
  ParameterVector parameters(*model, NominalX_B31B(robot.model12) * robot.X_BC, robot.X_TE);
  return {std::move(model), std::move(parameters)};
}

IdentificationOutcome IdentifyRobot(const RobotDescription& robot, ModelKind kind,
                                    const std::vector<DatasetRow>& rows,
                                    const IdentificationOptions& options, int valid_count,
                                    uint64_t seed) {
  const AprioriModel apriori = AprioriModelOf(robot, kind);
  const DatasetSplit split = SplitDataset(rows, valid_count, seed);
  IdentificationOutcome out =
      Identify(*apriori.model, apriori.parameters.X_BC(), apriori.parameters.X_TE(), split.calib,
               split.valid, options);
  out.result.log.insert(out.result.log.begin(), split.how);
  return out;
}

namespace {

// The Model 12 result as a Model 12 parameter vector of the robot's model.
ParameterVector Model12ParametersOf(const RobotDescription& robot,
                                    const IdentificationResult& model12_result) {
  const Model12 model12(robot.model12, robot.assembly);
  ParameterVector p12(model12, model12_result.X_BC, model12_result.X_TE);
  Eigen::VectorXd v = p12.values();
  for (const ResultParameter& rp : model12_result.parameters) {
    const int index = p12.IndexOf(rp.name);
    if (index >= 0 && index < p12.kinematic_count()) v[index] = rp.value;
  }
  p12.set_values(v);
  return p12;
}

// The Model 12 result's held-out poses, unless the rows carry a `set` column or the result
// lists none; every other pose is in the fit, those Model 12 rejected included.
DatasetSplit SplitAsModel12Result(const IdentificationResult& model12_result,
                                  const std::vector<DatasetRow>& rows) {
  const bool has_set =
      std::any_of(rows.begin(), rows.end(), [](const DatasetRow& r) { return r.set.has_value(); });
  const std::vector<int64_t>& valid = model12_result.valid_poses;
  if (has_set || valid.empty()) return SplitDataset(rows);
  DatasetSplit split;
  for (const DatasetRow& row : rows) {
    const bool held_out = std::find(valid.begin(), valid.end(), row.pose_id) != valid.end();
    (held_out ? split.valid : split.calib).push_back(row);
  }
  split.how = "split as the Model 12 result";
  return split;
}

}  // namespace

IdentificationOutcome IdentifyModel31FromModel12(const RobotDescription& robot,
                                                 const IdentificationResult& model12_result,
                                                 const std::vector<DatasetRow>& rows,
                                                 const IdentificationOptions& options) {
  RequireModel12Result(model12_result, "", "a Model 31 identification from Model 12");
  AprioriModel model31 = AprioriModelOf(robot, ModelKind::k31);
  const ParameterVector start =
      ConvertModel12To31(Model12ParametersOf(robot, model12_result), model31.model.get());
  const DatasetSplit split = SplitAsModel12Result(model12_result, rows);
  IdentificationOutcome out = IdentifyFromStart(*model31.model, model31.parameters, start,
                                                split.calib, split.valid, options);
  out.result.log.insert(out.result.log.begin(), "started from the Model 12 result; " + split.how);
  return out;
}

ModelPairOutcome IdentifyModel12Then31(const RobotDescription& robot,
                                       const std::vector<DatasetRow>& rows,
                                       const IdentificationOptions& options) {
  IdentificationOutcome model12 = IdentifyRobot(robot, ModelKind::k12, rows, options);
  IdentificationOutcome model31 = IdentifyModel31FromModel12(robot, model12.result, rows, options);
  return {std::move(model12), std::move(model31)};
}

std::string IdentificationSummary::FullReport() const {
  std::string s = fmt::format("identification: {} ({}), {} iterations, {:.3f} s\n",
                              usable ? "usable" : "NOT usable", message, iterations, seconds);
  for (const StageSummary& stage : stages) {
    fmt::format_to(std::back_inserter(s),
                   "stage {} on {} poses: {}, residual RMS {:.6g} -> {:.6g}\n", stage.name,
                   stage.poses, stage.message, stage.rms_before, stage.rms_after);
    for (const std::string& f : stage.fixed)
      fmt::format_to(std::back_inserter(s), "  fixed {}\n", f);
    for (const MinimizerReport& m : stage.minimizers) {
      fmt::format_to(std::back_inserter(s),
                     "  {}: {} iterations, {} evaluations, cost {:.6g} -> {:.6g}, {}, {:.2f} ms\n",
                     m.name, m.iterations, m.evaluations, m.initial_cost, m.final_cost,
                     m.stop_reason, m.seconds * 1e3);
    }
  }
  fmt::format_to(std::back_inserter(s), "final cost {:.6g}, chi2/dof {:.4g}\n", final_cost,
                 chi2_per_dof);
  return s;
}

}  // namespace h4::host

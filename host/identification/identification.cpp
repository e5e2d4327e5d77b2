// The staged identification pipeline; see identification.h. Result filling and the
// validation figures live in identification_report.cpp.
#include "host/identification/identification.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <stdexcept>

#include "host/identification/identification_report.h"
#include "host/identification/identified_robot.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host {
namespace {

std::string Printf(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Rms(const Eigen::VectorXd& r) {
  return r.size() > 0 ? std::sqrt(r.squaredNorm() / static_cast<double>(r.size())) : 0.0;
}

// Names are checked up front (RequireIdentifiableInput): every one is known here.
void FixUserParameters(const IdentificationOptions& options, ParameterVector* p) {
  for (const std::string& name : options.fixed_parameters) {
    const int index = p->IndexOf(name);
    if (index >= 0) p->Fix(index, "fixed by the user");
  }
}

// The preconditions of IdentifyFromStart that are the caller's input, not the solver's
// outcome: calibration poses to fit, and fixed-parameter names the model has (a typo
// silently ignored would identify a parameter the user meant to keep).
void RequireIdentifiableInput(const KinematicModel& model, const ParameterVector& start,
                              const std::vector<DatasetRow>& calib,
                              const IdentificationOptions& options) {
  if (calib.size() < kMinimumCalibrationPoses) {
    throw std::invalid_argument("identification needs at least " +
                                std::to_string(kMinimumCalibrationPoses) +
                                " calibration poses, got " + std::to_string(calib.size()) +
                                " (rows with set 'valid' are held out)");
  }
  for (const std::string& name : options.fixed_parameters) {
    if (start.IndexOf(name) >= 0) continue;
    std::string known;
    for (const std::string& n : start.names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("cannot fix '" + name + "': not a parameter of " +
                                ModelLabel(model.kind()) + "; the parameters are: " + known);
  }
}

}  // namespace

// The rows the identifiability analysis uses: each measured pose made exactly consistent
// with the start point (joints from the IK of the measured pose, X_CT re-predicted from
// the 4-DoF pose). Identifiability is a property of the model and the pose set; on the
// raw rows the measurement noise (a tilt of X_BE of ~1e-4 rad) would lift exact null
// directions (X_BC.tz + X_TE.tz, the board tilt under eq. (3)) off zero. Rows the start
// model cannot reach are left as measured.
std::vector<DatasetRow> ConsistentRows(const KinematicModel& model, const ParameterVector& p,
                                       const std::vector<DatasetRow>& rows) {
  std::unique_ptr<KinematicModel> start = model.Clone();
  p.ApplyTo(start.get());
  const RigidTransform X_BC = p.X_BC(), X_TE = p.X_TE();
  std::vector<DatasetRow> out = rows;
  for (DatasetRow& row : out) {
    const EePose x = EePoseFromMeasurement(X_BC, row.X_CT, X_TE).x;
    const IkResult ik = start->InverseKinematics(x);
    if (!ik.ok()) continue;
    for (size_t i = 0; i < 4; ++i) row.q[i] = ik.q[static_cast<Eigen::Index>(i)];
    row.X_CT = PredictedBoardPose(X_BC, x, X_TE);
  }
  return out;
}

namespace {

// A stage whose parameters are all fixed (the user fixed X_BC and X_TE in a placement
// stage, or every parameter): there is nothing to minimise, the start is the solution.
StageSummary NothingToFit(const IdentificationCost& cost, const ParameterVector& p,
                          std::chrono::steady_clock::time_point stage_start, StageSummary* stage,
                          SolutionJacobian* solution) {
  Eigen::VectorXd r;
  Eigen::MatrixXd* J_solution = solution != nullptr ? &solution->J : nullptr;
  std::string why;
  if (!cost.Evaluate(p, &r, J_solution, &why)) {
    stage->evaluable = false;
    stage->message = "cannot evaluate the cost: " + why;
    return *stage;
  }
  if (solution != nullptr) solution->r = r;
  stage->rms_after = Rms(r);
  stage->ok = true;
  stage->message = "nothing to fit: every parameter of this stage is fixed";
  stage->seconds = SecondsSince(stage_start);
  return *stage;
}

// One cost stage: identifiability at the start, NLopt, LM polish. `p` carries the values
// in and out; its mask on return is this stage's. `placement_only` fixes the kinematics.
// A parameter the analysis fixes takes its value in `reference` (the start: the a priori
// after the prior analysis, or the --from result): common/README.md, "Fixed parameters keep
// their a priori value". Without this, an earlier stage whose cost does not share the
// null direction would leave it wherever that stage drifted it. `solution` (may be null)
// receives the residuals and Jacobian at the stage's solution, computed once here for
// the outlier check, the covariance and the predicted accuracy.
StageSummary RunStage(CostKind kind, bool placement_only, const KinematicModel& model,
                      const std::vector<DatasetRow>& rows, const IdentificationOptions& options,
                      const ParameterVector& reference, ParameterVector* p,
                      IdentifiabilityReport* identifiability, SolutionJacobian* solution) {
  const auto stage_start = std::chrono::steady_clock::now();
  StageSummary stage;
  stage.cost = kind;
  stage.name = std::string(ToString(kind)) + (placement_only ? " (placement)" : "");
  stage.poses = static_cast<int>(rows.size());
  const IdentificationCost cost(kind, model, rows, options.cost);
  p->FreeAll();
  FixUserParameters(options, p);
  if (placement_only) {
    for (int k = 0; k < p->kinematic_count(); ++k) p->Fix(k, "placement stage");
  }
  Eigen::VectorXd r;
  std::string why;
  if (!cost.Evaluate(*p, &r, nullptr, &why)) {
    stage.evaluable = false;
    stage.message =
        "cannot evaluate the " + std::string(ToString(kind)) + " cost at the start: " + why;
    return stage;
  }
  stage.rms_before = Rms(r);
  if (p->free_count() == 0) return NothingToFit(cost, *p, stage_start, &stage, solution);
  const auto analysis_start = std::chrono::steady_clock::now();
  const IdentificationCost analysis_cost(kind, model, ConsistentRows(model, *p, rows),
                                         options.cost);
  Eigen::VectorXd r_analysis;
  Eigen::MatrixXd J_analysis;
  if (!analysis_cost.Evaluate(*p, &r_analysis, &J_analysis)) {
    cost.Evaluate(*p, &r_analysis, &J_analysis);  // evaluable: checked above
  }
  IdentifiabilityReport report =
      AnalyzeIdentifiability(J_analysis, model.kind(), options.identifiability, p);
  Eigen::VectorXd values = p->values();
  for (const FixedByAnalysis& f : report.fixed) {
    stage.fixed.push_back(f.name + ": " + f.reason);
    const int index = p->IndexOf(f.name);
    if (index >= 0) values[index] = reference.values()[index];
  }
  p->set_values(values);
  if (identifiability != nullptr) *identifiability = report;
  stage.analysis_seconds = SecondsSince(analysis_start);

  // r(v) on the free values; the parameter vector and the full Jacobian are buffers reused
  // across evaluations (a ParameterVector copy per call costs ~90 string allocations).
  const std::vector<int> free = p->FreeIndices();
  ParameterVector work = *p;
  Eigen::VectorXd values_buffer = p->values();
  Eigen::MatrixXd J_all;
  const ResidualFunction f = [&](const Eigen::VectorXd& v, Eigen::VectorXd* res,
                                 Eigen::MatrixXd* J_free) {
    for (size_t k = 0; k < free.size(); ++k) {
      values_buffer[free[k]] = v[static_cast<Eigen::Index>(k)];
    }
    work.set_values(values_buffer);
    if (J_free == nullptr) return cost.Evaluate(work, res, nullptr);
    if (!cost.Evaluate(work, res, &J_all)) return false;
    J_free->resize(J_all.rows(), static_cast<Eigen::Index>(free.size()));
    for (size_t k = 0; k < free.size(); ++k) {
      J_free->col(static_cast<Eigen::Index>(k)) = J_all.col(free[k]);
    }
    return true;
  };
  // NLopt to tight tolerances: alone (no polish), or as the fallback when LM fails.
  NloptOptions tight = options.nlopt;
  tight.relative_cost_tolerance = 1e-12;
  tight.relative_step_tolerance = 1e-12;
  tight.max_evaluations = std::max(options.nlopt.max_evaluations, 2000);
  Eigen::VectorXd v = p->FreeValues();
  bool converged = false;
  const bool use_nlopt = options.nlopt.algorithm != "none";
  if (use_nlopt) {
    stage.minimizers.push_back(
        MinimizeWithNlopt(f, options.lm_polish ? options.nlopt : tight, &v, options.progress));
    converged = stage.minimizers.back().converged;
  }
  if (options.lm_polish) {
    stage.minimizers.push_back(MinimizeWithLevenbergMarquardt(f, options.lm, &v, options.progress));
    converged = stage.minimizers.back().converged;
    if (!converged && use_nlopt) {
      // Fallback: NLopt to the end from where LM stopped, then LM again.
      stage.minimizers.push_back(MinimizeWithNlopt(f, tight, &v, options.progress));
      stage.minimizers.push_back(
          MinimizeWithLevenbergMarquardt(f, options.lm, &v, options.progress));
      converged = stage.minimizers.back().converged;
    }
  }
  p->SetFreeValues(v);
  Eigen::MatrixXd* J_solution = solution != nullptr ? &solution->J : nullptr;
  if (!cost.Evaluate(*p, &r, J_solution, &why)) {
    stage.evaluable = false;
    stage.message = "cannot evaluate the cost at the solution: " + why;
    return stage;
  }
  if (solution != nullptr) solution->r = r;
  stage.rms_after = Rms(r);
  stage.ok = converged;
  stage.message =
      converged ? "converged" : "did not converge: " + stage.minimizers.back().stop_reason;
  stage.seconds = SecondsSince(stage_start);
  return stage;
}

// One log line per stage: what ran, how many iterations and evaluations, the costs.
std::string StageLogLine(const StageSummary& stage) {
  std::string line = "stage " + stage.name + ": " + stage.message +
                     Printf(", residual RMS %.4g -> %.4g", stage.rms_before, stage.rms_after);
  for (const MinimizerReport& m : stage.minimizers) {
    line += "; " + m.name + " " + std::to_string(m.iterations) + " iterations, " +
            std::to_string(m.evaluations) + " evaluations, cost " +
            Printf("%.6g -> %.6g", m.initial_cost, m.final_cost) + " (" + m.stop_reason + ")";
  }
  return line + Printf(", %.2f ms", stage.seconds * 1e3);
}

// Per-pose residual norms of r (residuals_per_pose rows per pose).
std::vector<double> PoseResidualNorms(const Eigen::VectorXd& r, int residuals_per_pose) {
  std::vector<double> norms;
  const Eigen::Index m = residuals_per_pose;
  for (Eigen::Index j = 0; j + m <= r.size(); j += m) norms.push_back(r.segment(j, m).norm());
  return norms;
}

}  // namespace

bool IdentificationOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why != nullptr) *why = "identification options: " + message;
    return false;
  };
  if (nlopt.algorithm == "none" && !lm_polish) return fail("no minimiser (nlopt none, no LM)");
  std::string algorithm_why;
  if (!IsValidNloptAlgorithm(nlopt.algorithm, &algorithm_why)) return fail(algorithm_why);
  if (!(nlopt.relative_cost_tolerance > 0) || !(nlopt.relative_step_tolerance > 0)) {
    return fail("nlopt tolerances must be positive");
  }
  if (nlopt.max_evaluations <= 0) return fail("nlopt.max_evaluations must be positive");
  if (lm.max_iterations <= 0) return fail("lm.max_iterations must be positive");
  if (!(cost.default_sigma_t > 0) || !(cost.default_sigma_r > 0)) {
    return fail("default sigmas must be positive");
  }
  if (!(identifiability.relative_singular_value_threshold > 0 &&
        identifiability.relative_singular_value_threshold < 1)) {
    return fail("identifiability threshold must be in (0, 1)");
  }
  if (reject_outliers && !(outlier_factor > 1.0)) return fail("outlier_factor must exceed 1");
  if (!(max_rejected_fraction >= 0 && max_rejected_fraction < 1)) {
    return fail("max_rejected_fraction must be in [0, 1)");
  }
  if (!(correlation_threshold > 0 && correlation_threshold < 1)) {
    return fail("correlation_threshold must be in (0, 1)");
  }
  return true;
}

IdentificationOutcome IdentifyFromStart(const KinematicModel& model, const ParameterVector& apriori,
                                        const ParameterVector& start,
                                        const std::vector<DatasetRow>& calib,
                                        const std::vector<DatasetRow>& valid,
                                        const IdentificationOptions& options) {
  RequireIdentifiableInput(model, start, calib, options);
  const auto clock_start = std::chrono::steady_clock::now();
  IdentificationOutcome out{{}, {}, start, {}, {}, {}};
  IdentificationSummary& summary = out.summary;
  std::vector<std::string>& log = out.result.log;
  std::string why;
  if (!options.IsValid(&why)) {
    summary.message = why;
    FillResult(model, apriori, out.parameters, calib, valid, {}, options, &out);
    return out;
  }
  ParameterVector p = start;
  std::vector<DatasetRow> rows = calib;
  std::vector<int64_t> rejected;

  // Warm-up stages, then the estimator; the first stage may fit the placement alone first.
  std::vector<std::pair<CostKind, bool>> plan;
  for (CostKind kind : options.warmup_stages) plan.emplace_back(kind, false);
  plan.emplace_back(options.estimator, false);
  if (options.placement_first) plan.insert(plan.begin(), {plan.front().first, true});
  bool final_ok = false;
  SolutionJacobian solution;  // the estimator's r and J at the final solution, on `rows`
  for (size_t s = 0; s < plan.size(); ++s) {
    const bool is_final = s + 1 == plan.size();
    StageSummary stage =
        RunStage(plan[s].first, plan[s].second, model, rows, options, start, &p,
                 is_final ? &out.identifiability : nullptr, is_final ? &solution : nullptr);
    log.push_back(StageLogLine(stage));
    summary.stages.push_back(stage);
    if (!stage.evaluable) {
      summary.message = "stage " + stage.name + " failed: " + stage.message;
      FillResult(model, apriori, p, calib, valid, rejected, options, &out);
      return out;
    }
    final_ok = stage.ok;
  }

  // Outlier rejection on the estimator's per-pose residuals, then refits.
  for (int round = 0; options.reject_outliers && round < options.max_outlier_rounds; ++round) {
    const auto outlier_start = std::chrono::steady_clock::now();
    const std::vector<double> norms =
        PoseResidualNorms(solution.r, IdentificationCost::ResidualsPerPose(options.estimator));
    summary.outlier_seconds += SecondsSince(outlier_start);
    if (norms.empty()) break;
    std::vector<double> sorted = norms;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    const double limit = options.outlier_factor * sorted[sorted.size() / 2];
    std::vector<DatasetRow> kept;
    std::vector<int64_t> newly;
    for (size_t j = 0; j < rows.size(); ++j) {
      (norms[j] > limit ? newly.push_back(rows[j].pose_id), void() : kept.push_back(rows[j]));
    }
    if (newly.empty()) break;
    const double max_rejected = options.max_rejected_fraction * static_cast<double>(calib.size());
    if (static_cast<double>(rejected.size() + newly.size()) > max_rejected) {
      log.push_back("outlier rejection stopped: it would reject more than " +
                    Printf("%.0f%% of the poses", 100.0 * options.max_rejected_fraction));
      break;
    }
    std::string ids;
    for (int64_t id : newly) ids += (ids.empty() ? "" : " ") + std::to_string(id);
    log.push_back("rejected poses " + ids + Printf(" (residual norm above %.3g)", limit));
    rejected.insert(rejected.end(), newly.begin(), newly.end());
    rows = kept;
    StageSummary stage = RunStage(options.estimator, false, model, rows, options, start, &p,
                                  &out.identifiability, &solution);
    stage.name += " (after rejection)";
    log.push_back(StageLogLine(stage));
    summary.stages.push_back(stage);
    final_ok = stage.ok;
  }

  for (const StageSummary& stage : summary.stages) {
    for (const MinimizerReport& m : stage.minimizers) summary.iterations += m.iterations;
  }
  if (!summary.stages.empty() && !summary.stages.back().minimizers.empty()) {
    summary.final_cost = summary.stages.back().minimizers.back().final_cost;
  }
  std::vector<DatasetRow> used;
  for (const DatasetRow& row : calib) {
    if (std::find(rejected.begin(), rejected.end(), row.pose_id) == rejected.end())
      used.push_back(row);
  }
  out.parameters = p;
  const auto report_start = std::chrono::steady_clock::now();
  // `used` is `rows` (calib in order, rejected removed), on which `solution` was computed.
  FillResult(model, apriori, p, used, valid, rejected, options, &out, &solution);
  summary.report_seconds = SecondsSince(report_start);
  summary.chi2_per_dof = out.uncertainty.chi2_per_dof;
  summary.usable = final_ok && out.uncertainty.ok;
  if (summary.message.empty()) {
    summary.message = summary.usable ? "converged"
                      : !final_ok    ? "the final stage did not converge"
                                     : "no covariance at the solution (rank-deficient Jacobian)";
  }
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
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
  split.how = std::to_string(n_valid) + " validation poses drawn at random (seed " +
              std::to_string(seed) + ")";
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

IdentificationOutcome IdentifyModel31FromModel12(const RobotDescription& robot,
                                                 const IdentificationResult& model12_result,
                                                 const std::vector<DatasetRow>& rows,
                                                 const IdentificationOptions& options) {
  RequireModel12Result(model12_result, "", "--from");
  AprioriModel model31 = AprioriModelOf(robot, ModelKind::k31);
  const ParameterVector& apriori = model31.parameters;
  // The Model 12 result as a parameter vector, then its nominal Model 31.
  Model12 model12(robot.model12, robot.assembly);
  ParameterVector p12(model12, model12_result.X_BC, model12_result.X_TE);
  for (const ResultParameter& rp : model12_result.parameters) {
    const int index = p12.IndexOf(rp.name);
    if (index >= 0 && index < p12.kinematic_count()) {
      Eigen::VectorXd v = p12.values();
      v[index] = rp.value;
      p12.set_values(v);
    }
  }
  const ParameterVector start = ConvertModel12To31(p12, model31.model.get());
  // Reuse the Model 12 split unless the rows say otherwise.
  DatasetSplit split;
  const bool has_set =
      std::any_of(rows.begin(), rows.end(), [](const DatasetRow& r) { return r.set.has_value(); });
  if (has_set || model12_result.valid_poses.empty()) {
    split = SplitDataset(rows);
  } else {
    for (const DatasetRow& row : rows) {
      const auto& v = model12_result.valid_poses;
      (std::find(v.begin(), v.end(), row.pose_id) != v.end() ? split.valid : split.calib)
          .push_back(row);
    }
    split.how = "split as the Model 12 result";
  }
  IdentificationOutcome out =
      IdentifyFromStart(*model31.model, apriori, start, split.calib, split.valid, options);
  out.result.log.insert(out.result.log.begin(), "started from the Model 12 result; " + split.how);
  return out;
}

}  // namespace h4::host

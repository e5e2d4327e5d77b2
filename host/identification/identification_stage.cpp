// One identification stage; see identification_stage.h.
#include "host/identification/identification_stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "common/timing/clock.h"
#include "host/identification/identification.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {
namespace {

double Rms(const Eigen::VectorXd& r) {
  return r.size() > 0 ? std::sqrt(r.squaredNorm() / static_cast<double>(r.size())) : 0.0;
}

StageSummary NewStageSummary(const PlannedStage& planned, const std::vector<DatasetRow>& rows) {
  StageSummary stage;
  stage.cost = planned.cost;
  stage.name = std::string(ToString(planned.cost)) + (planned.placement_only ? " (placement)" : "");
  stage.poses = static_cast<int>(rows.size());
  return stage;
}

// Every parameter free but those the user fixes (names checked up front by
// IdentifyFromStart) and, in a placement stage, the kinematics.
void SetStageMask(const IdentificationOptions& options, const PlannedStage& planned,
                  ParameterVector* p) {
  p->FreeAll();
  for (const std::string& name : options.fixed_parameters) {
    const int index = p->IndexOf(name);
    if (index >= 0) p->Fix(index, "fixed by the user");
  }
  if (planned.placement_only) {
    for (int k = 0; k < p->kinematic_count(); ++k) p->Fix(k, "placement stage");
  }
}

// The residuals at p, and their Jacobian into `solution` when it is non-null; false (with
// the stage marked not evaluable) when the cost cannot be evaluated there.
bool EvaluateAtSolution(IdentificationCost* cost, const ParameterVector& p,
                        SolutionJacobian* solution, StageSummary* stage, const char* where) {
  Eigen::VectorXd r;
  Eigen::MatrixXd* J_solution = solution != nullptr ? &solution->J : nullptr;
  std::string why;
  if (!cost->Evaluate(p, &r, J_solution, &why)) {
    stage->evaluable = false;
    stage->message = std::string("cannot evaluate the cost") + where + ": " + why;
    return false;
  }
  if (solution != nullptr) solution->r = r;
  stage->rms_after = Rms(r);
  return true;
}

// A stage whose parameters are all fixed (the user fixed X_BC and X_TE in a placement
// stage, or every parameter): there is nothing to minimise, the start is the solution.
StageSummary NothingToFit(IdentificationCost* cost, const ParameterVector& p,
                          std::chrono::steady_clock::time_point stage_start,
                          SolutionJacobian* solution, StageSummary stage) {
  if (!EvaluateAtSolution(cost, p, solution, &stage, "")) return stage;
  stage.ok = true;
  stage.message = "nothing to fit: every parameter of this stage is fixed";
  stage.seconds = SecondsSince(stage_start);
  return stage;
}

// The identifiability analysis at the start point, on the rows made consistent with it
// (ConsistentRows); a parameter it fixes takes its value in context.reference. Without
// that, an earlier stage whose cost does not share the null direction would leave it
// wherever that stage drifted it. The stage's own cost is the fallback when a consistent
// row is out of reach (it is evaluable there: checked before).
IdentifiabilityReport FixUnidentifiable(const StageContext& context, const PlannedStage& planned,
                                        const std::vector<DatasetRow>& rows,
                                        IdentificationCost* cost, ParameterVector* p,
                                        StageSummary* stage) {
  const auto analysis_start = std::chrono::steady_clock::now();
  IdentificationCost analysis_cost(planned.cost, context.model,
                                   ConsistentRows(context.model, *p, rows), context.options.cost);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!analysis_cost.Evaluate(*p, &r, &J)) cost->Evaluate(*p, &r, &J);
  IdentifiabilityReport report =
      AnalyzeIdentifiability(J, context.model.kind(), context.options.identifiability, p);
  Eigen::VectorXd values = p->values();
  for (const FixedByAnalysis& f : report.fixed) {
    stage->fixed.push_back(f.name + ": " + f.reason);
    const int index = p->IndexOf(f.name);
    if (index >= 0) values[index] = context.reference.values()[index];
  }
  p->set_values(values);
  stage->analysis_seconds = SecondsSince(analysis_start);
  return report;
}

// NLopt to tight tolerances: alone (no polish), or as the fallback when LM fails.
NloptOptions TightNloptOptions(const NloptOptions& loose) {
  NloptOptions tight = loose;
  tight.relative_cost_tolerance = 1e-12;
  tight.relative_step_tolerance = 1e-12;
  tight.max_evaluations = std::max(loose.max_evaluations, 2000);
  return tight;
}

// NLopt (loose when LM polishes after it), then LM; when LM does not converge, NLopt to
// the end from where LM stopped, then LM again. Returns whether the last one converged.
bool Minimize(const IdentificationOptions& options, IdentificationCost* cost, ParameterVector* p,
              StageSummary* stage) {
  FreeParameterResiduals residuals(cost, *p);
  const ResidualFunction f = [&residuals](const Eigen::VectorXd& v, Eigen::VectorXd* r,
                                          Eigen::MatrixXd* J) { return residuals(v, r, J); };
  const NloptOptions tight = TightNloptOptions(options.nlopt);
  std::vector<MinimizerReport>& runs = stage->minimizers;
  Eigen::VectorXd v = p->FreeValues();
  const bool use_nlopt = options.nlopt.algorithm != "none";
  if (use_nlopt) {
    runs.push_back(
        MinimizeWithNlopt(f, options.lm_polish ? options.nlopt : tight, &v, options.progress));
  }
  if (options.lm_polish) {
    runs.push_back(MinimizeWithLevenbergMarquardt(f, options.lm, &v, options.progress));
    if (!runs.back().converged && use_nlopt) {
      runs.push_back(MinimizeWithNlopt(f, tight, &v, options.progress));
      runs.push_back(MinimizeWithLevenbergMarquardt(f, options.lm, &v, options.progress));
    }
  }
  p->SetFreeValues(v);
  return !runs.empty() && runs.back().converged;
}

}  // namespace

std::vector<PlannedStage> PlanStages(const IdentificationOptions& options) {
  std::vector<PlannedStage> plan;
  for (CostKind kind : options.warmup_stages) plan.push_back({kind, false});
  plan.push_back({options.estimator, false});
  if (options.placement_first) plan.insert(plan.begin(), {plan.front().cost, true});
  return plan;
}

StageSummary RunStage(const StageContext& context, const PlannedStage& planned,
                      const std::vector<DatasetRow>& rows, ParameterVector* p,
                      FinalStageOutputs* final_outputs) {
  const auto stage_start = std::chrono::steady_clock::now();
  StageSummary stage = NewStageSummary(planned, rows);
  IdentificationCost cost(planned.cost, context.model, rows, context.options.cost);
  SetStageMask(context.options, planned, p);
  Eigen::VectorXd r;
  std::string why;
  if (!cost.Evaluate(*p, &r, nullptr, &why)) {
    stage.evaluable = false;
    stage.message =
        "cannot evaluate the " + std::string(ToString(planned.cost)) + " cost at the start: " + why;
    return stage;
  }
  stage.rms_before = Rms(r);
  SolutionJacobian* solution = final_outputs != nullptr ? &final_outputs->solution : nullptr;
  if (p->free_count() == 0) return NothingToFit(&cost, *p, stage_start, solution, stage);
  IdentifiabilityReport report = FixUnidentifiable(context, planned, rows, &cost, p, &stage);
  if (final_outputs != nullptr) final_outputs->identifiability = std::move(report);
  const bool converged = Minimize(context.options, &cost, p, &stage);
  if (!EvaluateAtSolution(&cost, *p, solution, &stage, " at the solution")) return stage;
  stage.ok = converged;
  stage.message =
      converged ? "converged" : "did not converge: " + stage.minimizers.back().stop_reason;
  stage.seconds = SecondsSince(stage_start);
  return stage;
}

std::string StageLogLine(const StageSummary& stage) {
  std::string line = fmt::format("stage {}: {}, residual RMS {:.4g} -> {:.4g}", stage.name,
                                 stage.message, stage.rms_before, stage.rms_after);
  for (const MinimizerReport& m : stage.minimizers) {
    line += fmt::format("; {} {} iterations, {} evaluations, cost {:.6g} -> {:.6g} ({})", m.name,
                        m.iterations, m.evaluations, m.initial_cost, m.final_cost, m.stop_reason);
  }
  return line + fmt::format(", {:.2f} ms", stage.seconds * 1e3);
}

// Identifiability is a property of the model and the pose set; on the raw rows the
// measurement noise (a tilt of X_BE of ~1e-4 rad) would lift exact null directions
// (X_BC.tz + X_TE.tz, the board tilt under eq. (3)) off zero. Rows the start model cannot
// reach are left as measured.
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

}  // namespace h4::host

// Identification timing on the paper's 81-pose grid (simulated, paper noise, all poses for
// calibration), all in one run so that ratios hold on a loaded machine:
//  - the whole pipeline for Models 12 and 31 from the rough a priori, with and without
//    the k-fold cross-validation (default: NLopt
//    LD_LBFGS loosely, then the Levenberg-Marquardt polish, per stage; and LM alone,
//    `--algorithm none`), with per-phase counters (analysis, minimisers, report, ms);
//  - the final measurement-space stage alone, from the same start: the default NLopt stage
//    (loose), this project's LM, NLopt alone to the minimum, and Ceres (an analytic
//    CostFunction wrapping the same residuals and Jacobian);
//  - the forward kinematics of the 81 grid poses with a perturbed Model 31 (what the
//    measurement-space stage and the validation solve per evaluation);
//  - the corner path (`identify --corners`) for Model 31 on the 81 poses x the legacy 6x6
//    board's 144 corners, camera file with the typical-mix error, from the pose path's
//    Model 31 result: corner fits, poses measured again, cross-validation (CPU time).
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "common/board/board_model.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/identification/corner_identification.h"
#include "host/identification/identification.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/corner_campaign.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

#ifdef H4_HAVE_CERES
#include <ceres/ceres.h>
#endif

namespace h4::host {
namespace {

struct Problem {
  std::unique_ptr<KinematicModel> model;
  ParameterVector apriori;
  std::vector<DatasetRow> rows;
  ParameterVector stage_start;  // the measurement stage's start point and mask
};

Problem MakeProblem(ModelKind model_kind) {
  const RobotDescription apriori_robot = PaperAprioriRobot();
  const SimulatedRobot truth =
      MakeTrueRobot(apriori_robot, model_kind == ModelKind::k31 ? TrueGeometry::kPerturbedModel31
                                                                : TrueGeometry::kPerturbedModel12);
  DatasetOptions data_options;
  data_options.valid_count = 0;
  std::vector<DatasetRow> rows = SimulateDataset(truth, GridPosePlan(), data_options).rows;
  AprioriModel apriori_model = AprioriModelOf(apriori_robot, model_kind);
  std::unique_ptr<KinematicModel> model = std::move(apriori_model.model);
  ParameterVector apriori = apriori_model.parameters;
  // The start of the final stage: the pipeline without its final (measurement) stage.
  IdentificationOptions warmup;
  warmup.estimator = CostKind::kImplicit;
  warmup.warmup_stages.clear();
  warmup.reject_outliers = false;
  ParameterVector start =
      Identify(*model, apriori.X_BC(), apriori.X_TE(), rows, {}, warmup).parameters;
  // Its mask: the measurement stage's identifiability analysis.
  start.FreeAll();
  IdentificationCost cost(CostKind::kMeasurement, *model, ConsistentRows(*model, start, rows));
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  cost.Evaluate(start, &r, &J);
  AnalyzeIdentifiability(J, model_kind, {}, &start);
  return {.model = std::move(model), .apriori = apriori, .rows = rows, .stage_start = start};
}

const Problem& GetProblem(ModelKind model_kind) {
  static const Problem p12 = MakeProblem(ModelKind::k12);
  static const Problem p31 = MakeProblem(ModelKind::k31);
  return model_kind == ModelKind::k31 ? p31 : p12;
}

void RunPipeline(benchmark::State& state, ModelKind model_kind, const std::string& algorithm,
                 int folds = CrossValidationOptions{}.folds) {
  const Problem& p = GetProblem(model_kind);
  IdentificationOptions options;
  options.nlopt.algorithm = algorithm;
  options.cross_validation.folds = folds;
  double cost = 0.0, cv_seconds = 0.0;
  bool usable = true;
  IdentificationSummary last;
  for (auto _ : state) {
    IdentificationOutcome out =
        Identify(*p.model, p.apriori.X_BC(), p.apriori.X_TE(), p.rows, {}, options);
    cost = out.summary.final_cost;
    usable = usable && out.summary.usable;
    cv_seconds = out.cross_validation.seconds;
    last = std::move(out.summary);
  }
  // The k-fold cross-validation (folds refitted from the full fit; the outlier check reuses
  // it): its share of the pipeline, wall ms.
  state.counters["cv_ms"] = 1e3 * cv_seconds;
  // Where the time goes in the last run (wall ms): identifiability analyses, NLopt and LM
  // over all stages, the outlier check and the report (covariance, re-check, residuals).
  double analysis = 0.0, nlopt = 0.0, lm = 0.0;
  for (const StageSummary& stage : last.stages) {
    analysis += stage.analysis_seconds;
    for (const MinimizerReport& m : stage.minimizers) {
      (m.name.rfind("nlopt", 0) == 0 ? nlopt : lm) += m.seconds;
    }
  }
  state.counters["final_cost"] = cost;
  state.counters["usable"] = usable ? 1 : 0;
  state.counters["analysis_ms"] = 1e3 * analysis;
  state.counters["nlopt_ms"] = 1e3 * nlopt;
  state.counters["lm_ms"] = 1e3 * lm;
  state.counters["report_ms"] = 1e3 * (last.report_seconds + last.outlier_seconds);
}

void BM_IdentifyModel12(benchmark::State& state) { RunPipeline(state, ModelKind::k12, "LD_LBFGS"); }
void BM_IdentifyModel31(benchmark::State& state) { RunPipeline(state, ModelKind::k31, "LD_LBFGS"); }
void BM_IdentifyModel12LmOnly(benchmark::State& state) {
  RunPipeline(state, ModelKind::k12, "none");
}
// The pipeline without cross-validation (`--folds 0`, the in-sample outlier check): what
// one fit costs, against which the default's cross-validation is measured.
void BM_IdentifyModel12NoCrossValidation(benchmark::State& state) {
  RunPipeline(state, ModelKind::k12, "LD_LBFGS", 0);
}
void BM_IdentifyModel31NoCrossValidation(benchmark::State& state) {
  RunPipeline(state, ModelKind::k31, "LD_LBFGS", 0);
}
void BM_IdentifyModel31LmOnly(benchmark::State& state) {
  RunPipeline(state, ModelKind::k31, "none");
}

// The measurement-space stage alone, from the same start: the residual function on the free
// values the pipeline's stages use (FreeParameterResiduals).
void StageWithLm(benchmark::State& state, ModelKind model_kind) {
  const Problem& p = GetProblem(model_kind);
  MinimizerReport report;
  for (auto _ : state) {
    // A fresh cost per run: no forward kinematics warm start carried between runs.
    IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
    const ResidualFunction f = FreeParameterResiduals(&cost, p.stage_start);
    Eigen::VectorXd v = p.stage_start.FreeValues();
    report = MinimizeWithLevenbergMarquardt(f, LmOptions{}, &v);
  }
  state.counters["final_cost"] = report.final_cost;
  state.counters["iterations"] = report.iterations;
  state.counters["evaluations"] = report.evaluations;
}

// `to_the_end`: NLopt alone to the minimum (tight tolerances); else the pipeline's loose
// NLopt stage that precedes the LM polish.
void StageWithNlopt(benchmark::State& state, ModelKind model_kind, bool to_the_end) {
  const Problem& p = GetProblem(model_kind);
  MinimizerReport report;
  NloptOptions options;
  if (to_the_end) {
    options.max_evaluations = 2000;
    options.relative_cost_tolerance = 1e-12;
    options.relative_step_tolerance = 1e-12;
  }
  for (auto _ : state) {
    IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
    const ResidualFunction f = FreeParameterResiduals(&cost, p.stage_start);
    Eigen::VectorXd v = p.stage_start.FreeValues();
    report = MinimizeWithNlopt(f, options, &v);
  }
  state.counters["final_cost"] = report.final_cost;
  state.counters["evaluations"] = report.evaluations;
}

void BM_MeasurementStageLmModel12(benchmark::State& state) { StageWithLm(state, ModelKind::k12); }
void BM_MeasurementStageLmModel31(benchmark::State& state) { StageWithLm(state, ModelKind::k31); }
void BM_MeasurementStageNloptLooseModel31(benchmark::State& state) {
  StageWithNlopt(state, ModelKind::k31, false);
}
void BM_MeasurementStageNloptAloneModel31(benchmark::State& state) {
  StageWithNlopt(state, ModelKind::k31, true);
}

// 81 forward kinematics (Newton on the IKM, forward_kinematics.h) from the default guess,
// the joints from the true perturbed Model 31's inverse kinematics on the paper grid.
void BM_ForwardKinematicsPaperGrid(benchmark::State& state) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31);
  const std::unique_ptr<KinematicModel> model = truth.MakeModel();
  std::vector<JointVector> joints;
  for (const PlannedPose& pose : GridPosePlan()) {
    joints.push_back(model->InverseKinematics(EePoseInB31(pose.x, truth.X_ModelB())).q);
  }
  int failed = 0;
  for (auto _ : state) {
    for (const JointVector& q : joints) {
      const FkResult fk = ForwardKinematics(*model, q);
      failed += fk.ok() ? 0 : 1;
      benchmark::DoNotOptimize(fk.x);
    }
  }
  if (failed > 0) state.SkipWithError("a forward kinematics did not converge");
  state.counters["poses"] = static_cast<double>(joints.size());
}
BENCHMARK(BM_ForwardKinematicsPaperGrid)->Unit(benchmark::kMicrosecond);

#ifdef H4_HAVE_CERES
// All residuals of the measurement cost as one analytic Ceres cost over the free values.
class MeasurementCostFunction final : public ceres::CostFunction {
 public:
  explicit MeasurementCostFunction(const ResidualFunction& f, int residuals, int parameters)
      : f_(f) {
    set_num_residuals(residuals);
    mutable_parameter_block_sizes()->push_back(parameters);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int n = parameter_block_sizes()[0];
    const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(parameters[0], n);
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    const bool want_J = jacobians != nullptr && jacobians[0] != nullptr;
    if (!f_(v, &r, want_J ? &J : nullptr)) return false;
    Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()) = r;
    if (want_J) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], num_residuals(), n) = J;
    }
    return true;
  }

 private:
  ResidualFunction f_;
};

void StageWithCeres(benchmark::State& state, ModelKind model_kind) {
  const Problem& p = GetProblem(model_kind);
  ceres::Solver::Summary summary;
  for (auto _ : state) {
    IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
    const ResidualFunction f = FreeParameterResiduals(&cost, p.stage_start);
    Eigen::VectorXd v = p.stage_start.FreeValues();
    ceres::Problem problem;
    problem.AddResidualBlock(
        new MeasurementCostFunction(f, cost.residual_count(), static_cast<int>(v.size())), nullptr,
        v.data());
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.function_tolerance = 1e-14;  // as LmOptions: run to the same minimum
    options.parameter_tolerance = 1e-12;
    options.gradient_tolerance = 1e-14;
    options.max_num_iterations = 100;
    ceres::Solve(options, &problem, &summary);
  }
  state.counters["final_cost"] = summary.final_cost;
  state.counters["iterations"] = static_cast<double>(summary.iterations.size());
}

void BM_MeasurementStageCeresModel12(benchmark::State& state) {
  StageWithCeres(state, ModelKind::k12);
}
void BM_MeasurementStageCeresModel31(benchmark::State& state) {
  StageWithCeres(state, ModelKind::k31);
}
BENCHMARK(BM_MeasurementStageCeresModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageCeresModel31)->Unit(benchmark::kMillisecond);
#endif

// The corner path's inputs: a corner-level campaign through the true camera, poses solved
// with the typical-error file, and the pose path's Model 31 from Model 12.
struct CornerProblem {
  std::vector<DatasetRow> rows;
  std::vector<PoseCorners> corners;
  CameraIntrinsics file_camera;
  IdentificationOutcome pose_path;
};

const CornerProblem& GetCornerProblem() {
  static const CornerProblem problem = [] {
    const std::string boards = std::string(H4_SOURCE_DIR) + "/boards/";
    const CameraIntrinsics true_camera = ReadCameraYaml(boards + "sim_camera_1024x768.yaml");
    const CameraIntrinsics file_camera =
        ReadCameraYaml(boards + "sim_camera_1024x768_typical_error.yaml");
    const BoardModel board(ReadBoardYaml(boards + "aprilgrid_6x6_30mm.yaml"));
    const SimulatedRobot truth =
        MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31, {.seed = 1});
    const CornerCampaign campaign =
        SimulateCornerCampaign(truth, GridPosePlan(), board, true_camera, file_camera, {});
    return CornerProblem{
        campaign.rows, GroupCornersByRow(campaign.rows, campaign.corners, board, 0.05), file_camera,
        IdentifyModel12Then31(PaperAprioriRobot(), campaign.rows, {}).model31};
  }();
  return problem;
}

void BM_CornerPathModel31(benchmark::State& state) {
  const CornerProblem& p = GetCornerProblem();
  const AprioriModel apriori = AprioriModelOf(PaperAprioriRobot(), ModelKind::k31);
  for (auto _ : state) {
    const CornerPathOutcome path = IdentifyOnCorners(apriori, ModelKind::k31, p.pose_path, p.rows,
                                                     p.corners, p.file_camera, {}, {});
    if (!path.fit.ok) state.SkipWithError(path.fit.message.c_str());
    benchmark::DoNotOptimize(path);
  }
}
// Process CPU time: the cross-validation's folds may run on other threads.
BENCHMARK(BM_CornerPathModel31)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

BENCHMARK(BM_IdentifyModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel31)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel12NoCrossValidation)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel31NoCrossValidation)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel12LmOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel31LmOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageLmModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageLmModel31)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageNloptLooseModel31)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageNloptAloneModel31)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace h4::host

BENCHMARK_MAIN();

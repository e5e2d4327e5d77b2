// Identification timing on the paper's 81-pose grid (simulated, paper noise, all poses for
// calibration): the whole pipeline for Models 12 and 31 from the rough a priori, with the
// default LM engine and with NLopt first; and the final measurement-space stage alone,
// solved from the same start by this project's Levenberg-Marquardt and by Ceres (an
// analytic CostFunction wrapping the same residuals and Jacobian).
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "host/identification/identification.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/paper_scenario.h"
#include "host/simulation/pose_plan.h"
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

Problem MakeProblem(const std::string& model_name) {
  const RobotDescription apriori_robot = PaperAprioriRobot();
  const SimulatedRobot truth =
      MakeTrueRobot(apriori_robot, model_name == "31" ? TrueGeometry::kPerturbedModel31
                                                      : TrueGeometry::kPerturbedModel12);
  DatasetOptions data_options;
  data_options.valid_count = 0;
  std::vector<DatasetRow> rows = SimulateDataset(truth, GridPosePlan(), data_options).rows;
  std::unique_ptr<KinematicModel> model;
  ParameterVector apriori = AprioriParameters(apriori_robot, model_name, &model);
  // The start of the final stage: the pipeline without its final (measurement) stage.
  IdentificationOptions warmup;
  warmup.estimator = CostKind::kImplicit;
  warmup.warmup_stages.clear();
  warmup.reject_outliers = false;
  ParameterVector start =
      Identify(*model, apriori.X_BC(), apriori.X_TE(), rows, {}, warmup).parameters;
  // Its mask: the measurement stage's identifiability analysis.
  start.FreeAll();
  const IdentificationCost cost(CostKind::kMeasurement, *model,
                                ConsistentRows(*model, start, rows));
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  cost.Evaluate(start, &r, &J);
  AnalyzeIdentifiability(J, model_name, {}, &start);
  return {std::move(model), apriori, rows, start};
}

const Problem& GetProblem(const std::string& model_name) {
  static const Problem p12 = MakeProblem("12");
  static const Problem p31 = MakeProblem("31");
  return model_name == "31" ? p31 : p12;
}

void RunPipeline(benchmark::State& state, const std::string& model_name, bool nlopt_first) {
  const Problem& p = GetProblem(model_name);
  IdentificationOptions options;
  options.nlopt_first = nlopt_first;
  double cost = 0.0;
  bool usable = true;
  for (auto _ : state) {
    const IdentificationOutcome out =
        Identify(*p.model, p.apriori.X_BC(), p.apriori.X_TE(), p.rows, {}, options);
    cost = out.summary.final_cost;
    usable = usable && out.summary.usable;
  }
  state.counters["final_cost"] = cost;
  state.counters["usable"] = usable ? 1 : 0;
}

void BM_IdentifyModel12(benchmark::State& state) { RunPipeline(state, "12", false); }
void BM_IdentifyModel31(benchmark::State& state) { RunPipeline(state, "31", false); }
void BM_IdentifyModel12NloptFirst(benchmark::State& state) { RunPipeline(state, "12", true); }
void BM_IdentifyModel31NloptFirst(benchmark::State& state) { RunPipeline(state, "31", true); }

// The measurement-space stage alone, from the same start: residual function on the free values.
ResidualFunction StageFunction(const Problem& p, const IdentificationCost& cost) {
  return [&p, &cost](const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J_free) {
    ParameterVector q = p.stage_start;
    q.SetFreeValues(v);
    if (J_free == nullptr) return cost.Evaluate(q, r, nullptr);
    Eigen::MatrixXd J_all;
    if (!cost.Evaluate(q, r, &J_all)) return false;
    *J_free = FreeColumns(J_all, q);
    return true;
  };
}

void StageWithLm(benchmark::State& state, const std::string& model_name) {
  const Problem& p = GetProblem(model_name);
  const IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
  const ResidualFunction f = StageFunction(p, cost);
  MinimizerReport report;
  for (auto _ : state) {
    Eigen::VectorXd v = p.stage_start.FreeValues();
    report = MinimizeWithLevenbergMarquardt(f, LmOptions{}, &v);
  }
  state.counters["final_cost"] = report.final_cost;
  state.counters["iterations"] = report.iterations;
  state.counters["evaluations"] = report.evaluations;
}

void StageWithNlopt(benchmark::State& state, const std::string& model_name) {
  const Problem& p = GetProblem(model_name);
  const IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
  const ResidualFunction f = StageFunction(p, cost);
  MinimizerReport report;
  NloptOptions options;
  options.max_evaluations = 2000;
  for (auto _ : state) {
    Eigen::VectorXd v = p.stage_start.FreeValues();
    report = MinimizeWithNlopt(f, options, &v);
  }
  state.counters["final_cost"] = report.final_cost;
  state.counters["evaluations"] = report.evaluations;
}

void BM_MeasurementStageLmModel12(benchmark::State& state) { StageWithLm(state, "12"); }
void BM_MeasurementStageLmModel31(benchmark::State& state) { StageWithLm(state, "31"); }
void BM_MeasurementStageNloptModel31(benchmark::State& state) { StageWithNlopt(state, "31"); }

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

void StageWithCeres(benchmark::State& state, const std::string& model_name) {
  const Problem& p = GetProblem(model_name);
  const IdentificationCost cost(CostKind::kMeasurement, *p.model, p.rows);
  const ResidualFunction f = StageFunction(p, cost);
  ceres::Solver::Summary summary;
  for (auto _ : state) {
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

void BM_MeasurementStageCeresModel12(benchmark::State& state) { StageWithCeres(state, "12"); }
void BM_MeasurementStageCeresModel31(benchmark::State& state) { StageWithCeres(state, "31"); }
BENCHMARK(BM_MeasurementStageCeresModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageCeresModel31)->Unit(benchmark::kMillisecond);
#endif

BENCHMARK(BM_IdentifyModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel31)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel12NloptFirst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyModel31NloptFirst)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageLmModel12)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageLmModel31)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MeasurementStageNloptModel31)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace h4::host

BENCHMARK_MAIN();

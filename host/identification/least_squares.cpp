// NLopt and Levenberg-Marquardt minimisers of 0.5 |r|^2; see least_squares.h.
#include "host/identification/least_squares.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include <Eigen/Cholesky>
#include <nlopt.hpp>

#include "common/timing/clock.h"

namespace h4::host {
namespace {

struct NloptContext {
  const ResidualFunction* f = nullptr;
  const ProgressCallback* progress = nullptr;
  Eigen::VectorXd v0, scale, best_v;
  double best_cost = std::numeric_limits<double>::infinity();
  double failure_cost = 1e30;  // finite, so that line searches back off instead of crashing
  int evaluations = 0;
  bool stopped_by_callback = false;
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
};

double NloptObjective(unsigned n, const double* z, double* grad, void* data) {
  auto* c = static_cast<NloptContext*>(data);
  const Eigen::Map<const Eigen::VectorXd> z_map(z, n);
  const Eigen::VectorXd v = c->v0 + z_map.cwiseQuotient(c->scale);
  ++c->evaluations;
  const bool ok = (*c->f)(v, &c->r, grad != nullptr ? &c->J : nullptr);
  if (!ok) {
    if (grad != nullptr) std::fill(grad, grad + n, 0.0);
    return c->failure_cost;
  }
  const double cost = 0.5 * c->r.squaredNorm();
  if (grad != nullptr) {
    Eigen::Map<Eigen::VectorXd> g(grad, n);
    g = (c->J.transpose() * c->r).cwiseQuotient(c->scale);
  }
  if (cost < c->best_cost) {
    c->best_cost = cost;
    c->best_v = v;
  }
  if (*c->progress && !(*c->progress)("nlopt", c->evaluations, cost)) {
    c->stopped_by_callback = true;
    throw nlopt::forced_stop();
  }
  return cost;
}

}  // namespace

const std::vector<std::string>& NloptAlgorithmNames() {
  static const std::vector<std::string> names = {"LD_LBFGS",
                                                 "LD_SLSQP",
                                                 "LD_MMA",
                                                 "LD_CCSAQ",
                                                 "LD_VAR1",
                                                 "LD_VAR2",
                                                 "LD_TNEWTON",
                                                 "LD_TNEWTON_RESTART",
                                                 "LD_TNEWTON_PRECOND",
                                                 "LD_TNEWTON_PRECOND_RESTART",
                                                 "LN_BOBYQA",
                                                 "LN_NEWUOA",
                                                 "LN_COBYLA",
                                                 "LN_SBPLX",
                                                 "LN_NELDERMEAD",
                                                 "LN_PRAXIS"};
  return names;
}

bool IsValidNloptAlgorithm(const std::string& name, std::string* why) {
  const std::vector<std::string>& names = NloptAlgorithmNames();
  if (name == "none" || std::find(names.begin(), names.end(), name) != names.end()) return true;
  if (why != nullptr) {
    *why = "unknown NLopt algorithm \"" + name + "\": expected one of";
    for (const std::string& n : names) *why += " " + n;
    *why += ", or none";
  }
  return false;
}

Eigen::VectorXd ColumnScale(const Eigen::MatrixXd& J) {
  Eigen::VectorXd s = J.colwise().norm().transpose();
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (!(s[k] > 0.0) || !std::isfinite(s[k])) s[k] = 1.0;
  }
  return s;
}

MinimizerReport MinimizeWithNlopt(const ResidualFunction& f, const NloptOptions& options,
                                  Eigen::VectorXd* v, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  MinimizerReport report;
  report.name = "nlopt " + options.algorithm;
  NloptContext c;
  c.f = &f;
  c.progress = &progress;
  c.v0 = *v;
  c.best_v = *v;
  if (!f(*v, &c.r, &c.J)) {
    report.stop_reason = "residuals cannot be evaluated at the start point";
    return report;
  }
  report.initial_cost = report.final_cost = c.best_cost = 0.5 * c.r.squaredNorm();
  c.failure_cost = std::max(1e30, 1e10 * report.initial_cost);
  c.scale = ColumnScale(c.J);
  const unsigned n = static_cast<unsigned>(v->size());
  try {
    nlopt::opt opt(options.algorithm.c_str(), n);
    opt.set_min_objective(NloptObjective, &c);
    opt.set_maxeval(options.max_evaluations);
    opt.set_ftol_rel(options.relative_cost_tolerance);
    opt.set_xtol_rel(options.relative_step_tolerance);
    std::vector<double> z(n, 0.0);
    double cost = 0.0;
    const nlopt::result result = opt.optimize(z, cost);
    report.stop_reason = nlopt_result_to_string(static_cast<nlopt_result>(result));
    report.converged = result == nlopt::SUCCESS || result == nlopt::FTOL_REACHED ||
                       result == nlopt::XTOL_REACHED || result == nlopt::STOPVAL_REACHED;
  } catch (const nlopt::roundoff_limited&) {
    // The optimum is reached to within rounding: as good as converged.
    report.stop_reason = "ROUNDOFF_LIMITED";
    report.converged = true;
  } catch (const nlopt::forced_stop&) {
    report.stop_reason = c.stopped_by_callback ? "stopped by the progress callback" : "FORCED_STOP";
  } catch (const std::exception& e) {
    report.stop_reason = std::string("nlopt: ") + e.what();
  }
  *v = c.best_v;
  report.final_cost = c.best_cost;
  report.evaluations = report.iterations = c.evaluations;
  report.seconds = SecondsSince(start);
  return report;
}

namespace {

// The Levenberg-Marquardt iterate and its buffers, reused across iterations.
struct LmIterate {
  Eigen::VectorXd r, r_trial, g, dz, v_trial, scale;
  Eigen::MatrixXd J, A, A_damped;
  double cost = 0.0;
  double lambda = 0.0;
  double nu = 2.0;
};

// A = D^-1 J^T J D^-1 and g = D^-1 J^T r at the iterate, D the column scale, which never
// shrinks (Moré); A by one symmetric rank update (half a product).
void FormScaledNormalEquations(LmIterate* it) {
  it->scale = it->scale.cwiseMax(ColumnScale(it->J));
  const Eigen::Index n = it->J.cols();
  it->A.setZero(n, n);
  it->A.selfadjointView<Eigen::Lower>().rankUpdate(it->J.transpose());
  it->A.triangularView<Eigen::StrictlyUpper>() = it->A.transpose();
  const Eigen::VectorXd inverse_scale = it->scale.cwiseInverse();
  it->A = inverse_scale.asDiagonal() * it->A * inverse_scale.asDiagonal();
  it->g.noalias() = it->J.transpose() * it->r;
  it->g = it->g.cwiseProduct(inverse_scale);
}

// Moves the iterate to the trial point with Nielsen's damping update; true when the
// relative decrease is below the cost tolerance.
bool AcceptTrial(double cost_trial, double predicted, const LmOptions& options, Eigen::VectorXd* v,
                 LmIterate* it) {
  const double rho = predicted > 0 ? (it->cost - cost_trial) / predicted : 1.0;
  const double decrease = (it->cost - cost_trial) / std::max(it->cost, 1e-300);
  v->swap(it->v_trial);
  it->r.swap(it->r_trial);
  it->cost = cost_trial;
  it->lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
  it->nu = 2.0;
  return decrease < options.cost_tolerance;
}

struct LmStep {
  bool accepted = false;    ///< the iterate moved
  bool small_step = false;  ///< the step or the decrease fell below its tolerance
};

// Damped steps from the iterate, the damping growing, until one decreases the cost, the
// step vanishes, or the damping reaches its limit.
LmStep TryDampedSteps(const ResidualFunction& f, const LmOptions& options, Eigen::VectorXd* v,
                      LmIterate* it, int* evaluations) {
  LmStep step;
  const double z_norm = it->scale.cwiseProduct(*v).norm();
  while (!step.accepted) {
    it->A_damped = it->A;
    it->A_damped.diagonal().array() += it->lambda;
    it->dz = -it->A_damped.ldlt().solve(it->g);
    if (it->dz.norm() <= options.step_tolerance * (z_norm + options.step_tolerance)) {
      step.small_step = true;
      break;
    }
    it->v_trial = *v + it->dz.cwiseQuotient(it->scale);
    // Residuals only: a rejected trial (most of them near the minimum, where the damping
    // grows until the step vanishes) needs no Jacobian.
    ++*evaluations;
    const bool ok = it->dz.allFinite() && f(it->v_trial, &it->r_trial, nullptr);
    const double cost_trial = ok ? 0.5 * it->r_trial.squaredNorm() : 0.0;
    // Gain ratio: actual over predicted decrease of the quadratic model.
    const double predicted = -(it->g.dot(it->dz) + 0.5 * it->dz.dot(it->A * it->dz));
    if (ok && cost_trial < it->cost && f(it->v_trial, &it->r_trial, &it->J)) {
      step.accepted = true;
      step.small_step = AcceptTrial(cost_trial, predicted, options, v, it);
    } else {
      it->lambda *= it->nu;
      it->nu *= 2.0;
      if (it->lambda > 1e16) break;
    }
  }
  return step;
}

// Why the iterations stop converged after `step`, or null to go on.
const char* ConvergedReason(const LmStep& step) {
  if (step.small_step) return step.accepted ? "cost tolerance" : "step tolerance";
  // No decrease possible with the damping at its limit: at a minimum to within rounding.
  if (!step.accepted) return "no decrease possible (damping at its limit)";
  return nullptr;
}

}  // namespace

MinimizerReport MinimizeWithLevenbergMarquardt(const ResidualFunction& f, const LmOptions& options,
                                               Eigen::VectorXd* v,
                                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  MinimizerReport report;
  report.name = "levenberg-marquardt";
  LmIterate it;
  report.evaluations = 1;
  if (!f(*v, &it.r, &it.J)) {
    report.stop_reason = "residuals cannot be evaluated at the start point";
    return report;
  }
  it.cost = 0.5 * it.r.squaredNorm();
  report.initial_cost = report.final_cost = it.cost;
  it.scale = ColumnScale(it.J);
  it.lambda = options.initial_lambda;
  report.stop_reason = "iteration limit";
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    report.iterations = iteration;
    FormScaledNormalEquations(&it);
    if (it.g.cwiseAbs().maxCoeff() <= options.gradient_tolerance * (1.0 + it.cost)) {
      report.stop_reason = "gradient tolerance";
      report.converged = true;
      break;
    }
    const LmStep step = TryDampedSteps(f, options, v, &it, &report.evaluations);
    report.final_cost = it.cost;
    if (progress && !progress("levenberg-marquardt", iteration, it.cost)) {
      report.stop_reason = "stopped by the progress callback";
      break;
    }
    if (const char* reason = ConvergedReason(step)) {
      report.stop_reason = reason;
      report.converged = true;
      break;
    }
  }
  report.final_cost = it.cost;
  report.seconds = SecondsSince(start);
  return report;
}

}  // namespace h4::host

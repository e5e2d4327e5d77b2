// NLopt and Levenberg-Marquardt minimisers of 0.5 |r|^2; see least_squares.h.
#include "host/identification/least_squares.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include <Eigen/Cholesky>
#include <nlopt.hpp>

namespace h4::host {
namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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
  report.seconds = Seconds(start);
  return report;
}

MinimizerReport MinimizeWithLevenbergMarquardt(const ResidualFunction& f, const LmOptions& options,
                                               Eigen::VectorXd* v,
                                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  MinimizerReport report;
  report.name = "levenberg-marquardt";
  Eigen::VectorXd r, r_trial, g, dz, v_trial;
  Eigen::MatrixXd J, A, A_damped;
  report.evaluations = 1;
  if (!f(*v, &r, &J)) {
    report.stop_reason = "residuals cannot be evaluated at the start point";
    return report;
  }
  double cost = 0.5 * r.squaredNorm();
  report.initial_cost = report.final_cost = cost;
  Eigen::VectorXd scale = ColumnScale(J);
  double lambda = options.initial_lambda;
  double nu = 2.0;
  const Eigen::Index n = v->size();
  report.stop_reason = "iteration limit";
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    report.iterations = iteration;
    scale = scale.cwiseMax(ColumnScale(J));  // Moré: scaling never shrinks
    // A = D^-1 J^T J D^-1 and g = D^-1 J^T r: one symmetric rank update (half a product).
    A.setZero(n, n);
    A.selfadjointView<Eigen::Lower>().rankUpdate(J.transpose());
    A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
    const Eigen::VectorXd inverse_scale = scale.cwiseInverse();
    A = inverse_scale.asDiagonal() * A * inverse_scale.asDiagonal();
    g.noalias() = J.transpose() * r;
    g = g.cwiseProduct(inverse_scale);
    if (g.cwiseAbs().maxCoeff() <= options.gradient_tolerance * (1.0 + cost)) {
      report.stop_reason = "gradient tolerance";
      report.converged = true;
      break;
    }
    bool accepted = false;
    bool small_step = false;
    const double z_norm = scale.cwiseProduct(*v).norm();
    while (!accepted) {
      A_damped = A;
      A_damped.diagonal().array() += lambda;
      dz = -A_damped.ldlt().solve(g);
      if (dz.norm() <= options.step_tolerance * (z_norm + options.step_tolerance)) {
        small_step = true;
        break;
      }
      v_trial = *v + dz.cwiseQuotient(scale);
      // Residuals only: a rejected trial (most of them near the minimum, where the damping
      // grows until the step vanishes) needs no Jacobian.
      ++report.evaluations;
      const bool ok = dz.allFinite() && f(v_trial, &r_trial, nullptr);
      const double cost_trial = ok ? 0.5 * r_trial.squaredNorm() : 0.0;
      // Gain ratio: actual over predicted decrease of the quadratic model.
      const double predicted = -(g.dot(dz) + 0.5 * dz.dot(A * dz));
      if (ok && cost_trial < cost && f(v_trial, &r_trial, &J)) {
        const double rho = predicted > 0 ? (cost - cost_trial) / predicted : 1.0;
        const double decrease = (cost - cost_trial) / std::max(cost, 1e-300);
        v->swap(v_trial);
        r.swap(r_trial);
        cost = cost_trial;
        lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        nu = 2.0;
        accepted = true;
        if (decrease < options.cost_tolerance) small_step = true;
      } else {
        lambda *= nu;
        nu *= 2.0;
        if (lambda > 1e16) break;
      }
    }
    report.final_cost = cost;
    if (progress && !progress("levenberg-marquardt", iteration, cost)) {
      report.stop_reason = "stopped by the progress callback";
      break;
    }
    if (small_step) {
      report.stop_reason = accepted ? "cost tolerance" : "step tolerance";
      report.converged = true;
      break;
    }
    if (!accepted) {
      report.stop_reason = "no decrease possible (damping at its limit)";
      report.converged = true;  // at a minimum to within rounding
      break;
    }
  }
  report.final_cost = cost;
  report.seconds = Seconds(start);
  return report;
}

}  // namespace h4::host

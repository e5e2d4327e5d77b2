// The two minimisers of the identification's sum of squares 0.5 |r(v)|^2 over the free
// parameters v: NLopt (any gradient algorithm by name, on column-scaled variables as the
// paper scales its Jacobian) and a Levenberg-Marquardt on the column-scaled normal
// equations (the paper's solver), used as the final polish.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace h4::host {

/// r(v) and, when J is non-null, dr/dv. Returns false when r cannot be evaluated at v (a
/// pose out of reach): the minimisers then treat v as infinitely bad.
using ResidualFunction =
    std::function<bool(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J)>;

/// Called after each iteration with the stage name, iteration and cost; return false to stop.
using ProgressCallback = std::function<bool(const std::string& stage, int iteration, double cost)>;

struct NloptOptions {
  /// NLopt algorithm name without the "NLOPT_" prefix, one of NloptAlgorithmNames() (e.g.
  /// LD_LBFGS, LD_SLSQP, LN_BOBYQA); "none" skips NLopt.
  std::string algorithm = "LD_LBFGS";
  /// Defaults for NLopt before a Levenberg-Marquardt polish: loose, since it only has to
  /// bring the estimate into LM's basin, and tighter tolerances cost evaluations without
  /// saving LM iterations (docs/development.md#identification-speed).
  int max_evaluations = 100;              ///< per call
  double relative_cost_tolerance = 1e-1;  ///< NLopt ftol_rel
  double relative_step_tolerance = 1e-6;  ///< NLopt xtol_rel (scaled variables)
};

/// The local NLopt algorithms usable here (no bounds, no constraints): gradient-based LD_*
/// and derivative-free LN_* names.
const std::vector<std::string>& NloptAlgorithmNames();
/// True for "none" and NloptAlgorithmNames(); else false, with `why` listing the allowed names.
bool IsValidNloptAlgorithm(const std::string& name, std::string* why = nullptr);

struct LmOptions {
  int max_iterations = 100;
  double cost_tolerance = 1e-14;      ///< stop when the relative cost decrease is below
  double step_tolerance = 1e-12;      ///< stop when |dz| < tol * (|z| + tol), z scaled
  double gradient_tolerance = 1e-14;  ///< stop when max |J_s^T r| / (1 + cost) is below
  double initial_lambda = 1e-4;       ///< damping relative to the scaled unit diagonal
};

/// What one minimisation did.
struct MinimizerReport {
  std::string name;  ///< e.g. "nlopt LD_LBFGS" or "levenberg-marquardt"
  int iterations = 0;
  int evaluations = 0;
  double initial_cost = 0.0;  ///< 0.5 |r|^2
  double final_cost = 0.0;
  std::string stop_reason;
  bool converged = false;  ///< stopped on a tolerance (not iteration limit, not failure)
  double seconds = 0.0;
};

/// NLopt on z = D (v - v0), D = column norms of J(v0); v is updated in place to the best
/// point found (never worse than the start). Fails cleanly (converged = false) when the
/// algorithm name is unknown or r(v0) cannot be evaluated.
MinimizerReport MinimizeWithNlopt(const ResidualFunction& f, const NloptOptions& options,
                                  Eigen::VectorXd* v, const ProgressCallback& progress = {});

/// Levenberg-Marquardt with Moré's column scaling (running maximum of the column norms).
MinimizerReport MinimizeWithLevenbergMarquardt(const ResidualFunction& f, const LmOptions& options,
                                               Eigen::VectorXd* v,
                                               const ProgressCallback& progress = {});

/// Column norms of J, with zero columns given 1 (a parameter with no effect stays put).
Eigen::VectorXd ColumnScale(const Eigen::MatrixXd& J);

}  // namespace h4::host

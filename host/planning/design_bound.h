// How good ANY N poses of the candidates can be: a certified lower bound on the criterion the
// exchange of pose_design.h minimises (PlanForMeanAccuracy), so that a plan can be judged
// against what is possible, not only against the grid. The exchange is a local search; this
// bound is not.
//
// The criterion is L-optimality (I-optimality over the evaluated poses), averaged over the
// models k (the a priori robot and the drawn ones):
//   f = mean_k trace(A_k S_k^-1),  S_k = sum over the design's poses i of F_ik, plus E_k,
// with F_ik = B_ik^T B_ik the information of candidate i under model k (its 6 rows B_ik of
// information_model.h), A_k the sum of T_j^T T_j over the translation rows of the evaluated
// poses, and E_k the information of the poses measured already (DesignOptions::existing).
//
// Relaxation (Kiefer 1959, approximate designs): an exact design of N candidates, repeats
// allowed (so every design the exchange can give), has S_k = N M_k(w) + E_k with
// M_k(w) = sum_i w_i F_ik and w_i = (times candidate i is chosen) / N on the simplex. Over the
// whole simplex f(w) is convex (S -> trace(A S^-1) is convex on positive definite S, S is
// affine in w, and a mean of convex functions is convex), and its minimum f* is no higher
// than any exact design's criterion.
//
// f* is approached by the multiplicative algorithm (Silvey, Titterington and Torsney 1978;
// Yu 2010, "Monotonic convergence of a general algorithm for computing optimal designs",
// Annals of Statistics 38(3)):
//   w_i <- w_i d_i^(1/2) / sum_j w_j d_j^(1/2),  d_i = mean_k trace(F_ik S_k^-1 A_k S_k^-1),
// where -N d_i is the derivative of f by w_i. Yu proves the power 1/2 monotonic for A- and
// L-optimality of one model with nothing measured; for the mean over models or with measured
// poses it is only a heuristic step. The bound below does not depend on it converging.
//
// The certificate, for any weights w: convexity gives f(v) >= f(w) - N sum_i d_i (v_i - w_i)
// for every v of the simplex, hence (v a vertex)
//   f* >= f(w) - N (max_i d_i - sum_i w_i d_i)        (the Frank-Wolfe gap).
// With nothing measured f is homogeneous, f(c w) = f(w) / c, so N sum_i w_i d_i = f(w)
// (Euler) and the same inequality at c v, minimised over c > 0, gives the tighter
//   f* >= f(w)^2 / (N max_i d_i)                       (the efficiency bound: Atwood 1973;
// Pukelsheim 1993, Optimal Design of Experiments, ch. 7), f(w) / (N max_i d_i) being the
// efficiency of w. Both are true lower bounds whether or not the iteration has converged.
//
// Distinct poses (the exchange never chooses a candidate twice): w_i <= 1/N, a smaller
// relaxation and a tighter bound. The same two inequalities hold with v over the capped
// simplex instead of its vertices; the v that maximises sum_i d_i v_i there puts 1/N on the N
// largest d_i, so max_i d_i becomes their mean (a vertex of the capped simplex), for any w.
// The step is the multiplicative one clipped at 1/N, the rest rescaled to sum 1: its fixed
// points are the capped problem's optimality conditions (d_i equal where 0 < w_i < 1/N, no
// lower at the cap, no higher at 0); again only the certificate is relied upon.
#pragma once

#include <string>
#include <vector>

#include "host/planning/information_model.h"

namespace h4::host {

struct BoundOptions {
  int pose_count = 25;  ///< N: the bound is for designs of N poses (with the existing)
  /// Poses measured already (indices into every model, none a candidate), as
  /// DesignOptions::existing: their information is E_k.
  std::vector<int> existing;
  int max_iterations = 3000;
  /// Stop once the certified bound is within this fraction of the weights' criterion.
  double tolerance = 1e-3;
  /// The support: candidates whose weight is at least this (the rest fade geometrically).
  double support_weight = 1e-4;
  /// Each candidate at most once, as the exchange chooses (weights at most 1/N); false: the
  /// textbook approximate design, repeats allowed (a looser bound).
  bool distinct = true;

  bool IsValid(std::string* why) const;
};

struct DesignBound {
  /// f at the final weights (a design measure, not an N-pose design): mean_k trace(A_k S_k^-1).
  double criterion = 0.0;
  /// Certified: no design of options.pose_count candidates (with the existing) has a
  /// criterion below it. 0 when the candidates do not determine the parameters.
  double criterion_lower = 0.0;
  std::vector<double> weights;  ///< one per candidate, sum 1
  std::vector<int> support;     ///< candidates of weight >= options.support_weight, ascending
  int iterations = 0;
  bool converged = false;  ///< the bound reached (1 - tolerance) of the criterion

  /// criterion_lower / criterion: 1 at the optimum.
  double Efficiency() const { return criterion > 0.0 ? criterion_lower / criterion : 0.0; }
};

/// The bound for the mean criterion over `models` (the same poses in each, their own
/// Jacobians), the candidates being poses [0, candidate_count) and the criterion's A_k the
/// translation rows of the poses `evaluated`. Throws std::invalid_argument on invalid options,
/// no model, an existing pose among the candidates, or (distinct) fewer candidates than N.
DesignBound OptimalDesignBound(const std::vector<const InformationModel*>& models,
                               int candidate_count, const std::vector<int>& evaluated,
                               const BoundOptions& options);

/// One model (the a priori robot's alone).
DesignBound OptimalDesignBound(const InformationModel& info, int candidate_count,
                               const std::vector<int>& evaluated, const BoundOptions& options);

}  // namespace h4::host

// The optimal approximate design and its certified bound (design_bound.h).
#include "host/planning/design_bound.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include "common/text/invalid_reason.h"

namespace h4::host {

bool BoundOptions::IsValid(std::string* why) const {
  if (pose_count < 1) return Invalid(why, "pose_count must be >= 1");
  if (max_iterations < 0) return Invalid(why, "max_iterations must be >= 0");
  if (!(tolerance >= 0.0 && tolerance < 1.0)) return Invalid(why, "tolerance must be in [0, 1)");
  if (!(support_weight > 0.0 && support_weight <= 1.0)) {
    return Invalid(why, "support_weight must be in (0, 1]");
  }
  return true;
}

namespace {

constexpr int kRowsPerPose = 6;

// What the iteration needs of one model: its candidates' rows (6 per candidate), A_k (the
// evaluated poses' translation rows) and E_k (the poses measured already).
struct BoundModel {
  Eigen::MatrixXd candidate_rows;
  Eigen::MatrixXd A;
  Eigen::MatrixXd E;
};

BoundModel BoundModelOf(const InformationModel& info, int candidate_count,
                        const std::vector<int>& evaluated, const std::vector<int>& existing) {
  BoundModel model;
  model.candidate_rows =
      info.J_scaled.topRows(kRowsPerPose * static_cast<Eigen::Index>(candidate_count));
  const int k = info.parameter_count();
  model.A = Eigen::MatrixXd::Zero(k, k);
  for (int j : evaluated) {
    const Eigen::MatrixXd T = info.Block(j).bottomRows(3);
    model.A.noalias() += T.transpose() * T;
  }
  model.E = InformationMatrix(info, existing);
  return model;
}

// The criterion f and the derivatives d_i (design_bound.h) at the weights w.
struct Evaluation {
  bool ok = false;  ///< every S_k positive definite
  double criterion = std::numeric_limits<double>::infinity();
  Eigen::VectorXd d;
};

// S_k = N sum_i w_i B_i^T B_i + E_k, as (sqrt(N w_i) B_i)^T (sqrt(N w_i) B_i) stacked.
Eigen::MatrixXd DesignInformation(const BoundModel& model, const Eigen::VectorXd& w,
                                  int pose_count) {
  Eigen::VectorXd row_scale(model.candidate_rows.rows());
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    row_scale.segment<kRowsPerPose>(kRowsPerPose * i)
        .setConstant(std::sqrt(static_cast<double>(pose_count) * w[i]));
  }
  const Eigen::MatrixXd weighted = row_scale.asDiagonal() * model.candidate_rows;
  return weighted.transpose() * weighted + model.E;
}

Evaluation Evaluate(const std::vector<BoundModel>& models, const Eigen::VectorXd& w,
                    int pose_count) {
  Evaluation e;
  e.d = Eigen::VectorXd::Zero(w.size());
  double criterion = 0.0;
  const double per_model = 1.0 / static_cast<double>(models.size());
  for (const BoundModel& model : models) {
    const Eigen::LLT<Eigen::MatrixXd> llt(DesignInformation(model, w, pose_count));
    if (llt.info() != Eigen::Success) return e;
    const Eigen::MatrixXd S_inv_A = llt.solve(model.A);
    criterion += per_model * S_inv_A.trace();
    // G = S^-1 A S^-1; d_i = trace(B_i G B_i^T) = sum over B_i's rows b of b G b^T.
    const Eigen::MatrixXd G = llt.solve(S_inv_A.transpose());
    const Eigen::VectorXd row_terms =
        (model.candidate_rows * G).cwiseProduct(model.candidate_rows).rowwise().sum();
    e.d += per_model * row_terms.reshaped(kRowsPerPose, w.size()).colwise().sum().transpose();
  }
  e.ok = true;
  e.criterion = criterion;
  return e;
}

// The largest sum_i d_i v_i over the (capped) simplex: max_i d_i, or with distinct poses the
// mean of the N largest d_i (design_bound.h).
double LargestDirectionalDerivative(const Eigen::VectorXd& d, int pose_count, bool distinct) {
  if (!distinct) return d.maxCoeff();
  std::vector<double> values(d.data(), d.data() + d.size());
  const auto top = values.begin() + pose_count;
  std::nth_element(values.begin(), top - 1, values.end(), std::greater<>());
  return std::accumulate(values.begin(), top, 0.0) / pose_count;
}

// The certificate of design_bound.h: the efficiency bound when nothing is measured (f
// homogeneous), else the Frank-Wolfe gap; never negative (0 is a bound too).
double CertifiedLowerBound(const Evaluation& e, const Eigen::VectorXd& w,
                           const BoundOptions& options) {
  const double largest = LargestDirectionalDerivative(e.d, options.pose_count, options.distinct);
  const double n = static_cast<double>(options.pose_count);
  if (!(largest > 0.0)) return 0.0;
  if (options.existing.empty()) return e.criterion * e.criterion / (n * largest);
  return std::max(0.0, e.criterion - n * (largest - w.dot(e.d)));
}

// v scaled to sum 1 with no weight above cap: min(cap, t v_i), the largest clipped first
// (water-filling). cap * v.size() >= 1.
Eigen::VectorXd ScaledBelowCap(const Eigen::VectorXd& v, double cap) {
  std::vector<Eigen::Index> order(static_cast<size_t>(v.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return v[a] > v[b]; });
  Eigen::VectorXd w = Eigen::VectorXd::Constant(v.size(), cap);
  double left = 1.0, rest = v.sum();
  size_t clipped = 0;
  while (clipped < order.size() && rest > 0.0 && left / rest * v[order[clipped]] > cap) {
    left -= cap;
    rest -= v[order[clipped++]];
  }
  const double scale = rest > 0.0 ? left / rest : 0.0;
  for (size_t k = clipped; k < order.size(); ++k) w[order[k]] = scale * v[order[k]];
  return w;
}

// The multiplicative step (design_bound.h), clipped at 1/N for distinct poses.
Eigen::VectorXd MultiplicativeStep(const Eigen::VectorXd& w, const Eigen::VectorXd& d,
                                   const BoundOptions& options) {
  const Eigen::VectorXd v = w.cwiseProduct(d.cwiseMax(0.0).cwiseSqrt());
  if (options.distinct) return ScaledBelowCap(v, 1.0 / options.pose_count);
  return v / v.sum();
}

void CheckArguments(const std::vector<const InformationModel*>& models, int candidate_count,
                    const BoundOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("bound options: " + why);
  if (models.empty()) throw std::invalid_argument("design bound: no information model");
  if (candidate_count < 1 || candidate_count > models.front()->pose_count()) {
    throw std::invalid_argument(fmt::format("design bound: {} candidates of {} poses",
                                            candidate_count, models.front()->pose_count()));
  }
  if (options.distinct && options.pose_count > candidate_count) {
    throw std::invalid_argument(
        fmt::format("design bound: {} distinct poses asked of {} candidates", options.pose_count,
                    candidate_count));
  }
  for (int j : options.existing) {
    if (j < candidate_count || j >= models.front()->pose_count()) {
      throw std::invalid_argument("design bound: an existing pose must not be a candidate");
    }
  }
}

}  // namespace

DesignBound OptimalDesignBound(const std::vector<const InformationModel*>& models,
                               int candidate_count, const std::vector<int>& evaluated,
                               const BoundOptions& options) {
  CheckArguments(models, candidate_count, options);
  std::vector<BoundModel> bound_models;
  for (const InformationModel* info : models) {
    bound_models.push_back(BoundModelOf(*info, candidate_count, evaluated, options.existing));
  }
  // Uniform weights: every candidate's information in, so S_k is positive definite whenever
  // the candidates determine the parameters at all.
  Eigen::VectorXd w = Eigen::VectorXd::Constant(candidate_count, 1.0 / candidate_count);
  DesignBound bound;
  Evaluation e = Evaluate(bound_models, w, options.pose_count);
  if (!e.ok) {
    // The candidates do not determine the parameters: no design does, and 0 bounds it.
    bound.criterion = std::numeric_limits<double>::infinity();
  }
  while (e.ok) {
    bound.criterion = e.criterion;
    bound.criterion_lower = CertifiedLowerBound(e, w, options);
    bound.converged = bound.criterion_lower >= (1.0 - options.tolerance) * bound.criterion;
    if (bound.converged || bound.iterations == options.max_iterations) break;
    Eigen::VectorXd next = MultiplicativeStep(w, e.d, options);
    Evaluation next_e = Evaluate(bound_models, next, options.pose_count);
    if (!next_e.ok) break;  // keep the last weights that were evaluated
    w = std::move(next);
    e = std::move(next_e);
    ++bound.iterations;
  }
  bound.weights.assign(w.data(), w.data() + w.size());
  for (int i = 0; i < candidate_count; ++i) {
    if (w[i] >= options.support_weight) bound.support.push_back(i);
  }
  return bound;
}

DesignBound OptimalDesignBound(const InformationModel& info, int candidate_count,
                               const std::vector<int>& evaluated, const BoundOptions& options) {
  return OptimalDesignBound(std::vector<const InformationModel*>{&info}, candidate_count, evaluated,
                            options);
}

}  // namespace h4::host

// D-optimal pose design by exchange (pose_design.h).
#include "host/planning/pose_design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include "common/text/invalid_reason.h"

namespace h4::host {

bool DesignOptions::IsValid(std::string* why) const {
  if (pose_count < 1) return Invalid(why, "pose_count must be >= 1");
  if (max_exchanges < 0) return Invalid(why, "max_exchanges must be >= 0");
  if (restarts < 1) return Invalid(why, "restarts must be >= 1");
  if (!(ridge > 0.0 && ridge < 1.0)) return Invalid(why, "ridge must be in (0, 1)");
  return true;
}

double LogDet(const Eigen::MatrixXd& M) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  return 2.0 * llt.matrixLLT().diagonal().array().log().sum();
}

// A Fisher-Yates prefix written out, so that the draw does not depend on the standard
// library's shuffle.
std::vector<int> SeededSubset(int count, int n, uint64_t seed) {
  std::vector<int> order(static_cast<size_t>(count));
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  for (int i = 0; i < n; ++i) {
    const uint64_t span = static_cast<uint64_t>(count - i);
    const int k = i + static_cast<int>(rng() % span);
    std::swap(order[static_cast<size_t>(i)], order[static_cast<size_t>(k)]);
  }
  order.resize(static_cast<size_t>(n));
  return order;
}

namespace {

// For each candidate j, log det(I + A_j M^-1 A_j^T) (sign +1: the gain of adding it) or
// log det(I - A_j M^-1 A_j^T) (sign -1: the change of dropping it), by the matrix
// determinant lemma; W = A L^-T for M = L L^T makes each a 6 x 6 determinant.
std::vector<double> LogDetChanges(const InformationModel& info, const Eigen::MatrixXd& M,
                                  const std::vector<int>& poses, double sign) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  std::vector<double> change(poses.size(), -std::numeric_limits<double>::infinity());
  for (size_t n = 0; n < poses.size(); ++n) {
    const Eigen::MatrixXd W = llt.matrixL().solve(info.Block(poses[n]).transpose());
    const Eigen::Matrix<double, 6, 6> S =
        Eigen::Matrix<double, 6, 6>::Identity() + sign * (W.transpose() * W);
    change[n] = LogDet(S);
  }
  return change;
}

// For each pose j, the fall of trace(A M^-1) when it is added (sign +1),
// trace((I + G)^-1 H), or minus its rise when it is dropped (sign -1),
// -trace((I - G)^-1 H), with G = B M^-1 B^T and H = B M^-1 A M^-1 B^T for its block B
// (Woodbury): higher is better either way.
std::vector<double> AccuracyChanges(const InformationModel& info, const Eigen::MatrixXd& M,
                                    const Eigen::MatrixXd& A, const std::vector<int>& poses,
                                    double sign) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  std::vector<double> change(poses.size(), -std::numeric_limits<double>::infinity());
  for (size_t n = 0; n < poses.size(); ++n) {
    const Eigen::MatrixXd B = info.Block(poses[n]);
    const Eigen::MatrixXd X = llt.solve(B.transpose());  // M^-1 B^T
    const Eigen::Matrix<double, 6, 6> G = B * X;
    const Eigen::Matrix<double, 6, 6> H = X.transpose() * A * X;
    const Eigen::Matrix<double, 6, 6> S = Eigen::Matrix<double, 6, 6>::Identity() + sign * G;
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(S);
    if (sign < 0.0 && ldlt.vectorD().minCoeff() <= 1e-12) continue;  // dropping it: singular
    change[n] = sign * ldlt.solve(H).trace();
  }
  return change;
}

size_t ArgMax(const std::vector<double>& values) {
  return static_cast<size_t>(std::max_element(values.begin(), values.end()) - values.begin());
}

// `design` and the poses measured already.
std::vector<int> WithExisting(std::vector<int> design, const std::vector<int>& existing) {
  design.insert(design.end(), existing.begin(), existing.end());
  return design;
}

// The information matrices of `design` and `existing` under each model, plus each model's
// ridge.
std::vector<Eigen::MatrixXd> InformationMatrices(const std::vector<const InformationModel*>& models,
                                                 const std::vector<int>& design,
                                                 const std::vector<int>& existing,
                                                 const std::vector<double>& ridges) {
  std::vector<Eigen::MatrixXd> Ms;
  for (size_t k = 0; k < models.size(); ++k) {
    Ms.push_back(InformationMatrix(*models[k], WithExisting(design, existing), ridges[k]));
  }
  return Ms;
}

// The exchange: add the pose `scores` ranks best (sign +1) among those outside, drop the
// one it ranks best to drop (sign -1) among the design and the added, until the dropped is
// the added. Every model sees the same poses (one robot each, or one alone); the poses
// `existing` are in every information matrix and never exchanged.
template <typename Scores>
Design Exchange(const std::vector<const InformationModel*>& models, int candidate_count,
                std::vector<int> design, const std::vector<int>& existing,
                const std::vector<double>& ridges, int max_exchanges, Scores scores) {
  std::vector<char> in_design(static_cast<size_t>(candidate_count), 0);
  for (int j : design) in_design[static_cast<size_t>(j)] = 1;
  std::vector<Eigen::MatrixXd> Ms = InformationMatrices(models, design, existing, ridges);
  Design result;
  while (result.exchanges < max_exchanges) {
    std::vector<int> outside;
    for (int j = 0; j < candidate_count; ++j) {
      if (!in_design[static_cast<size_t>(j)]) outside.push_back(j);
    }
    if (outside.empty()) {
      result.converged = true;
      break;
    }
    const int added = outside[ArgMax(scores(Ms, outside, +1.0))];
    for (size_t k = 0; k < models.size(); ++k) {
      Ms[k].noalias() += models[k]->Block(added).transpose() * models[k]->Block(added);
    }
    design.push_back(added);
    const size_t drop_at = ArgMax(scores(Ms, design, -1.0));
    const int dropped = design[drop_at];
    design.erase(design.begin() + static_cast<std::ptrdiff_t>(drop_at));
    // Fresh: no drift from adding and removing.
    Ms = InformationMatrices(models, design, existing, ridges);
    if (dropped == added) {
      result.converged = true;
      break;
    }
    in_design[static_cast<size_t>(added)] = 1;
    in_design[static_cast<size_t>(dropped)] = 0;
    ++result.exchanges;
  }
  result.chosen = design;
  return result;
}

// options.ridge relative to the mean diagonal of all the candidates' information.
double RelativeRidge(const InformationModel& info, int candidate_count, double ridge) {
  return ridge *
         info.J_scaled.topRows(6 * static_cast<Eigen::Index>(candidate_count)).squaredNorm() /
         std::max(1, info.parameter_count());
}

// A = sum of T_j^T T_j over the translation rows of the poses `evaluated`.
Eigen::MatrixXd TargetTranslationWeight(const InformationModel& info,
                                        const std::vector<int>& evaluated) {
  const int k = info.parameter_count();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(k, k);
  for (int j : evaluated) {
    const Eigen::MatrixXd T = info.Block(j).bottomRows(3);
    A.noalias() += T.transpose() * T;
  }
  return A;
}

}  // namespace

Design PlanDOptimal(const InformationModel& info, int candidate_count,
                    const DesignOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("design options: " + why);
  if (candidate_count > info.pose_count() || options.pose_count > candidate_count) {
    throw std::invalid_argument(fmt::format("pose planning: {} poses asked of {} candidates",
                                            options.pose_count, candidate_count));
  }
  for (int j : options.existing) {
    if (j < candidate_count || j >= info.pose_count()) {
      throw std::invalid_argument("pose planning: an existing pose must not be a candidate");
    }
  }
  std::vector<int> design = SeededSubset(candidate_count, options.pose_count, options.seed);
  const std::vector<double> ridges = {RelativeRidge(info, candidate_count, options.ridge)};
  Design result =
      Exchange({&info}, candidate_count, design, options.existing, ridges, options.max_exchanges,
               [&](const std::vector<Eigen::MatrixXd>& Ms, const std::vector<int>& poses,
                   double sign) { return LogDetChanges(info, Ms[0], poses, sign); });
  design = result.chosen;
  std::sort(design.begin(), design.end());
  result.chosen = design;
  result.log_det = LogDet(InformationMatrix(info, WithExisting(design, options.existing)));
  return result;
}

Design PlanForAccuracy(const InformationModel& info, int candidate_count,
                       const std::vector<int>& evaluated, const DesignOptions& options) {
  return PlanForMeanAccuracy({&info}, candidate_count, evaluated, options);
}

Design PlanForMeanAccuracy(const std::vector<const InformationModel*>& models, int candidate_count,
                           const std::vector<int>& evaluated, const DesignOptions& options) {
  if (models.empty()) throw std::invalid_argument("pose planning: no information model");
  const Design start = PlanDOptimal(*models.front(), candidate_count, options);
  std::vector<double> ridges;
  std::vector<Eigen::MatrixXd> weights;
  for (const InformationModel* info : models) {
    ridges.push_back(RelativeRidge(*info, candidate_count, options.ridge));
    weights.push_back(TargetTranslationWeight(*info, evaluated));
  }
  // The mean over the models of trace(A_k M_k^-1): each term is a variance in measurement
  // sigmas (column scaling cancels), so the models add as robots of one prior.
  const auto mean_change = [&](const std::vector<Eigen::MatrixXd>& Ms,
                               const std::vector<int>& poses, double sign) {
    std::vector<double> total(poses.size(), 0.0);
    for (size_t k = 0; k < models.size(); ++k) {
      const std::vector<double> change =
          AccuracyChanges(*models[k], Ms[k], weights[k], poses, sign);
      for (size_t n = 0; n < poses.size(); ++n) total[n] += change[n];
    }
    return total;
  };
  Design result = Exchange(models, candidate_count, start.chosen, options.existing, ridges,
                           options.max_exchanges, mean_change);
  result.exchanges += start.exchanges;
  std::sort(result.chosen.begin(), result.chosen.end());
  result.log_det =
      LogDet(InformationMatrix(*models.front(), WithExisting(result.chosen, options.existing)));
  return result;
}

}  // namespace h4::host

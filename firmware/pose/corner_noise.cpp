// The corners' own error apart from the camera model's misfit; see corner_noise.h.
#include "firmware/pose/corner_noise.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/QR>

namespace h4::cam {
namespace {

// Monomials of the smooth field per axis: 1, s, t, s^2, s t, t^2.
constexpr int kFieldTerms = 6;
// Degrees of freedom the residuals must keep beyond the fit and the field to tell an excess.
constexpr Eigen::Index kMinSpareDegrees = 12;

// The field's columns: for each axis, the quadratic monomials of the corner's offset from the
// corners' centroid over their spread (so that the columns are of order 1).
Eigen::MatrixXd SmoothFieldColumns(const std::vector<CornerObservation>& corners) {
  const auto n = static_cast<Eigen::Index>(corners.size());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const CornerObservation& c : corners) centre += c.uv / static_cast<double>(n);
  double spread2 = 0;
  for (const CornerObservation& c : corners)
    spread2 += (c.uv - centre).squaredNorm() / static_cast<double>(n);
  const double spread = std::max(std::sqrt(spread2), 1.0);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * n, 2 * kFieldTerms);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d d = (corners[static_cast<size_t>(i)].uv - centre) / spread;
    const double s = d.x(), t = d.y();
    const double terms[kFieldTerms] = {1.0, s, t, s * s, s * t, t * t};
    for (int k = 0; k < kFieldTerms; ++k) {
      B(2 * i, k) = terms[k];
      B(2 * i + 1, kFieldTerms + k) = terms[k];
    }
  }
  return B;
}

}  // namespace

std::vector<std::vector<Eigen::Index>> CornersByEdgeGroup(
    const std::vector<CornerObservation>& corners) {
  std::vector<std::pair<int, Eigen::Index>> group_of;
  for (size_t i = 0; i < corners.size(); ++i) {
    const int group = corners[i].edge_group;
    group_of.emplace_back(group >= 0 ? group : -1 - static_cast<int>(i),
                          static_cast<Eigen::Index>(i));
  }
  std::sort(group_of.begin(), group_of.end());
  std::vector<std::vector<Eigen::Index>> groups;
  for (size_t k = 0; k < group_of.size(); ++k) {
    if (k == 0 || group_of[k].first != group_of[k - 1].first) groups.emplace_back();
    groups.back().push_back(group_of[k].second);
  }
  return groups;
}

double ExcessBeyondSmoothField(const std::vector<CornerObservation>& corners,
                               const Eigen::MatrixXd& J, const Eigen::VectorXd& r) {
  const Eigen::Index m = r.size();
  Eigen::MatrixXd F(m, J.cols() + 2 * kFieldTerms);
  F << J, SmoothFieldColumns(corners);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(F);
  const Eigen::Index rank = qr.rank();
  if (m - rank < kMinSpareDegrees) return -1.0;
  // Thin Q: an orthonormal basis of what the fit and the field can explain.
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, rank);
  const Eigen::VectorXd r_left = r - Q * (Q.transpose() * r);
  // The noise's own share of |r_left|^2: trace((I - Q Q^T) Sigma), Sigma = N N^T per group.
  double expected = 0, variance = 0;
  for (const std::vector<Eigen::Index>& group : CornersByEdgeGroup(corners)) {
    Eigen::MatrixXd explained = Eigen::MatrixXd::Zero(rank, CornerNoisePx::ColsAtCompileTime);
    Eigen::Matrix<double, 8, 8> gram = Eigen::Matrix<double, 8, 8>::Zero();
    for (const Eigen::Index i : group) {
      const CornerNoisePx& N = corners[static_cast<size_t>(i)].noise_px;
      explained += Q.middleRows(2 * i, 2).transpose() * N;
      gram += N.transpose() * N;
    }
    expected += gram.trace() - explained.squaredNorm();
    variance += 2.0 * gram.squaredNorm();
  }
  const double beyond = r_left.squaredNorm() - expected - 2.0 * std::sqrt(variance);
  return std::max(0.0, beyond) / static_cast<double>(m - rank);
}

}  // namespace h4::cam

// Covariance, standard deviations and correlations at the solution; see uncertainty.h.
// The inverse is taken on the column-scaled Jacobian J_s = J D^-1, so that metres and
// radians mixing does not cost accuracy: C = D^-1 (J_s^T J_s)^-1 D^-1, or D^-1 V S^-2 V^T
// D^-1 through the SVD when J_s is ill-conditioned.
#include "host/identification/uncertainty.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "host/identification/identifiability.h"
#include "host/identification/least_squares.h"

namespace h4::host {

Uncertainty ComputeUncertainty(const ParameterVector& p, const Eigen::VectorXd& r,
                               const Eigen::MatrixXd& J_full, bool weighted,
                               double correlation_threshold) {
  Uncertainty u;
  u.free_indices = p.FreeIndices();
  const Eigen::Index n = static_cast<Eigen::Index>(u.free_indices.size());
  const Eigen::Index m = r.size();
  if (n == 0 || m <= n) return u;
  const Eigen::MatrixXd J = FreeColumns(J_full, p);
  const Eigen::VectorXd scale = ColumnScale(J);
  // (J_s^T J_s)^-1 directly when the eigenvalues of J_s^T J_s show it well conditioned
  // (relative error ~ cond^2 eps, 1e-8 at worst); else through the SVD of J_s's QR factor,
  // which also decides rank deficiency.
  const Eigen::MatrixXd J_s = J * scale.cwiseInverse().asDiagonal();
  Eigen::VectorXd s;
  Eigen::MatrixXd C_scaled, gram;
  if (SingularValuesIfWellConditioned(J_s, 1e-4, &s, &gram)) {
    C_scaled = gram.llt().solve(Eigen::MatrixXd::Identity(n, n));
  } else {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(TallR(J_s), Eigen::ComputeFullV);
    s = svd.singularValues();
    if (!(s[n - 1] > 1e-12 * s[0])) return u;  // rank deficient: no meaningful covariance
    const Eigen::MatrixXd& V = svd.matrixV();
    C_scaled = V * s.cwiseAbs2().cwiseInverse().asDiagonal() * V.transpose();
  }
  u.condition_number = s[0] / s[n - 1];
  u.chi2_per_dof = r.squaredNorm() / static_cast<double>(m - n);
  // Weighted residuals: the covariance is (J^T J)^-1 when the pose sigmas are right; a
  // reduced chi-square above 1 is misfit the sigmas do not explain, and the parameters'
  // uncertainty grows with it (never shrinks below what the sigmas say).
  u.sigma2 = weighted ? std::max(1.0, u.chi2_per_dof) : u.chi2_per_dof;
  u.covariance =
      u.sigma2 * scale.cwiseInverse().asDiagonal() * C_scaled * scale.cwiseInverse().asDiagonal();
  u.std = u.covariance.diagonal().cwiseSqrt();
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = a + 1; b < n; ++b) {
      const double rho = u.covariance(a, b) / (u.std[a] * u.std[b]);
      if (std::abs(rho) > correlation_threshold) {
        u.correlations.push_back(
            {p.names()[static_cast<size_t>(u.free_indices[static_cast<size_t>(a)])],
             p.names()[static_cast<size_t>(u.free_indices[static_cast<size_t>(b)])], rho});
      }
    }
  }
  std::sort(u.correlations.begin(), u.correlations.end(),
            [](const CorrelatedPair& x, const CorrelatedPair& y) {
              return std::abs(x.correlation) > std::abs(y.correlation);
            });
  u.ok = u.std.allFinite();
  return u;
}

double PredictedPositionAccuracy(const Uncertainty& u, const Eigen::MatrixXd& J_point_full) {
  if (!u.ok || J_point_full.rows() < 3) return 0.0;
  Eigen::MatrixXd J(J_point_full.rows(), static_cast<Eigen::Index>(u.free_indices.size()));
  for (size_t k = 0; k < u.free_indices.size(); ++k) {
    J.col(static_cast<Eigen::Index>(k)) = J_point_full.col(u.free_indices[k]);
  }
  const Eigen::MatrixXd JC = J * u.covariance;
  double sum = 0.0;
  const Eigen::Index points = J.rows() / 3;
  for (Eigen::Index i = 0; i < points; ++i) {
    double trace = 0.0;
    for (Eigen::Index k = 3 * i; k < 3 * i + 3; ++k) trace += JC.row(k).dot(J.row(k));
    sum += trace;
  }
  return std::sqrt(sum / static_cast<double>(points));
}

}  // namespace h4::host

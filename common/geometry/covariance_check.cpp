// See covariance_check.h.
#include "common/geometry/covariance_check.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

namespace h4 {

std::string CovarianceProblem(const Eigen::MatrixXd& C) {
  if (C.rows() != C.cols()) return fmt::format("not square ({}x{})", C.rows(), C.cols());
  if (!C.allFinite()) return "a non-finite element";
  for (Eigen::Index i = 0; i < C.rows(); ++i) {
    if (!(C(i, i) >= 0.0)) return fmt::format("a negative variance on the diagonal ({})", i);
    for (Eigen::Index j = 0; j < i; ++j) {
      const double tolerance = 1e-9 * std::sqrt(C(i, i) * C(j, j)) + 1e-300;
      if (!(std::abs(C(i, j) - C(j, i)) <= tolerance)) {
        return fmt::format("not symmetric (elements ({}, {}) and ({}, {}) differ)", i, j, j, i);
      }
    }
  }
  if (C.size() == 0) return "";
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(C, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues().minCoeff();
  const double largest = eigen.eigenvalues().maxCoeff();
  if (smallest < -1e-9 * std::max(largest, 0.0)) {
    return fmt::format("not positive semi-definite: an eigenvalue is {:.6g}", smallest);
  }
  return "";
}

}  // namespace h4

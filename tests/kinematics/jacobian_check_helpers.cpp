// Central finite-difference check of analytic Jacobians; see jacobian_check_helpers.h.
#include "tests/kinematics/jacobian_check_helpers.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace h4::host::testing {

Eigen::MatrixXd FiniteDifferenceJacobian(const VectorFunction& f, const Eigen::VectorXd& x0,
                                         double step) {
  const Eigen::VectorXd f0 = f(x0);
  Eigen::MatrixXd J(f0.size(), x0.size());
  Eigen::VectorXd x = x0;
  for (Eigen::Index j = 0; j < x0.size(); ++j) {
    x[j] = x0[j] + step;
    const Eigen::VectorXd f_plus = f(x);
    x[j] = x0[j] - step;
    const Eigen::VectorXd f_minus = f(x);
    x[j] = x0[j];
    J.col(j) = (f_plus - f_minus) / (2.0 * step);
  }
  return J;
}

::testing::AssertionResult JacobianMatchesFiniteDifferences(const VectorFunction& f,
                                                            const Eigen::VectorXd& x0,
                                                            const Eigen::MatrixXd& J_analytic,
                                                            double step, double tolerance) {
  if (!(step > 0.0) || !(tolerance > 0.0)) {
    return ::testing::AssertionFailure() << "step and tolerance must be positive, got step " << step
                                         << ", tolerance " << tolerance;
  }
  const Eigen::MatrixXd J_fd = FiniteDifferenceJacobian(f, x0, step);
  if (J_fd.rows() != J_analytic.rows() || J_fd.cols() != J_analytic.cols()) {
    return ::testing::AssertionFailure()
           << "analytic Jacobian is " << J_analytic.rows() << "x" << J_analytic.cols()
           << " but f maps R^" << x0.size() << " to R^" << J_fd.rows() << " (expected "
           << J_fd.rows() << "x" << J_fd.cols() << ")";
  }
  struct Bad {
    Eigen::Index row, col;
    double analytic, numeric, excess;  // excess: error / allowed
  };
  std::vector<Bad> bad;
  for (Eigen::Index i = 0; i < J_fd.rows(); ++i) {
    for (Eigen::Index j = 0; j < J_fd.cols(); ++j) {
      const double a = J_analytic(i, j);
      const double n = J_fd(i, j);
      const double allowed = tolerance * std::max(1.0, std::abs(n));
      const double error = std::abs(a - n);
      if (!std::isfinite(a) || !std::isfinite(n) || !(error <= allowed)) {
        bad.push_back({i, j, a, n, std::isfinite(error) ? error / allowed : HUGE_VAL});
      }
    }
  }
  if (bad.empty()) return ::testing::AssertionSuccess();
  std::sort(bad.begin(), bad.end(), [](const Bad& x, const Bad& y) { return x.excess > y.excess; });
  // Doubles to 10 significant digits.
  std::string message = fmt::format(
      "{} of {} Jacobian entries differ from central finite differences (step {:.10g}, "
      "tolerance {:.10g} abs/rel); worst:",
      bad.size(), J_fd.size(), step, tolerance);
  for (size_t k = 0; k < std::min<size_t>(bad.size(), 8); ++k) {
    fmt::format_to(std::back_inserter(message), "\n  ({}, {}): analytic {:.10g}, numeric {:.10g}",
                   bad[k].row, bad[k].col, bad[k].analytic, bad[k].numeric);
  }
  return ::testing::AssertionFailure() << message;
}

::testing::AssertionResult ConstraintJacobiansMatchFiniteDifferences(const KinematicModel& model,
                                                                     const JointVector& q,
                                                                     const EePose& x) {
  Eigen::Matrix4d J_f_x;
  Eigen::Vector4d J_f_q;
  Eigen::MatrixXd J_f_xi;
  model.ConstraintJacobians(q, x, &J_f_x, &J_f_q, &J_f_xi);
  const double step = 1e-6, tolerance = 1e-8;
  ::testing::AssertionResult by_x = JacobianMatchesFiniteDifferences(
      [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return model.Constraints(q, v); }, x,
      J_f_x, step, tolerance);
  if (!by_x) return by_x << " (J_f_x)";
  ::testing::AssertionResult by_q = JacobianMatchesFiniteDifferences(
      [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return model.Constraints(v, x); }, q,
      Eigen::MatrixXd(J_f_q.asDiagonal()), step, tolerance);
  if (!by_q) return by_q << " (J_f_q)";
  const std::unique_ptr<KinematicModel> perturbed = model.Clone();
  ::testing::AssertionResult by_xi = JacobianMatchesFiniteDifferences(
      [&](const Eigen::VectorXd& xi) -> Eigen::VectorXd {
        perturbed->set_parameters(xi);
        return perturbed->Constraints(q, x);
      },
      model.parameters(), J_f_xi, step, tolerance);
  if (!by_xi) return by_xi << " (J_f_xi)";
  return ::testing::AssertionSuccess();
}

}  // namespace h4::host::testing

// Tests of the shared Jacobian check helper: it accepts a correct Jacobian and rejects
// a wrong entry, a wrong shape and a non-finite entry.
#include <cmath>

#include <gtest/gtest.h>

#include "tests/kinematics/jacobian_check_helpers.h"

namespace h4::host::testing {
namespace {

// f(x) = (x0^2 x1, sin(x1) + 3 x0) and its Jacobian.
Eigen::VectorXd F(const Eigen::VectorXd& x) {
  return Eigen::Vector2d(x[0] * x[0] * x[1], std::sin(x[1]) + 3.0 * x[0]);
}
Eigen::MatrixXd JF(const Eigen::VectorXd& x) {
  Eigen::MatrixXd J(2, 2);
  J << 2.0 * x[0] * x[1], x[0] * x[0], 3.0, std::cos(x[1]);
  return J;
}

TEST(JacobianCheck, AcceptsCorrectJacobian) {
  const Eigen::Vector2d x0(0.7, -1.3);
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(F, x0, JF(x0), 1e-6, 1e-7));
}

TEST(JacobianCheck, FiniteDifferencesAreSecondOrderAccurate) {
  const Eigen::Vector2d x0(0.7, -1.3);
  const Eigen::MatrixXd J_fd = FiniteDifferenceJacobian(F, x0, 1e-4);
  EXPECT_LT((J_fd - JF(x0)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(JacobianCheck, RejectsOneWrongEntry) {
  const Eigen::Vector2d x0(0.7, -1.3);
  Eigen::MatrixXd J = JF(x0);
  J(1, 0) += 1e-4;
  const auto result = JacobianMatchesFiniteDifferences(F, x0, J, 1e-6, 1e-6);
  EXPECT_FALSE(result);
  EXPECT_NE(std::string(result.message()).find("(1, 0)"), std::string::npos);
}

TEST(JacobianCheck, RejectsWrongShape) {
  const Eigen::Vector2d x0(0.7, -1.3);
  EXPECT_FALSE(JacobianMatchesFiniteDifferences(F, x0, Eigen::MatrixXd::Zero(2, 3), 1e-6, 1e-6));
}

TEST(JacobianCheck, RejectsNonFiniteEntry) {
  const Eigen::Vector2d x0(0.7, -1.3);
  Eigen::MatrixXd J = JF(x0);
  J(0, 1) = std::nan("");
  EXPECT_FALSE(JacobianMatchesFiniteDifferences(F, x0, J, 1e-6, 1e-6));
}

}  // namespace
}  // namespace h4::host::testing

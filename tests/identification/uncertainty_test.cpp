// ComputeUncertainty (host/identification/uncertainty.h) against the closed form of linear
// least squares: for r = J v - b at the solution, the covariance of the free parameters is
// s^2 (J^T J)^-1 with s^2 = |r|^2 / (m - n) (unweighted), or (J^T J)^-1 scaled by
// max(1, chi2/dof) when the residuals are already divided by their sigmas. Also on a
// Jacobian whose columns differ by eight orders of magnitude (metres against radians:
// the path through the SVD), a rank-deficient one, fixed parameters and correlations.
#include "host/identification/uncertainty.h"

#include <random>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

constexpr int kResiduals = 60;

/// A Model 12 parameter vector (25 parameters): only its size, names and mask matter here.
ParameterVector Parameters() {
  return ParameterVector(Model12(kPaperIdentifiedModel12), PaperX_BC(), PaperX_TE());
}

Eigen::MatrixXd RandomJacobian(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd J(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) J(i, j) = normal(rng);
  }
  return J;
}

/// The residual at the least-squares solution of J v = b for a random b.
Eigen::VectorXd ResidualAtSolution(const Eigen::MatrixXd& J, unsigned seed) {
  const Eigen::VectorXd b = RandomJacobian(static_cast<int>(J.rows()), 1, seed);
  const Eigen::VectorXd v = J.colPivHouseholderQr().solve(b);
  return J * v - b;
}

Eigen::MatrixXd ClosedForm(const Eigen::MatrixXd& J, double s2) {
  const Eigen::MatrixXd gram = J.transpose() * J;
  return s2 * gram.llt().solve(Eigen::MatrixXd::Identity(J.cols(), J.cols()));
}

double RelativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / b.norm();
}

TEST(ComputeUncertainty, UnweightedIsTheResidualVarianceTimesTheInverseGram) {
  const ParameterVector p = Parameters();
  const Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 1);
  const Eigen::VectorXd r = ResidualAtSolution(J, 2);
  const Uncertainty u = ComputeUncertainty(p, r, J, /*weighted=*/false);
  ASSERT_TRUE(u.ok);
  const double s2 = r.squaredNorm() / (kResiduals - p.size());
  EXPECT_NEAR(u.chi2_per_dof, s2, 1e-12 * s2);
  EXPECT_DOUBLE_EQ(u.sigma2, u.chi2_per_dof);
  EXPECT_LT(RelativeError(u.covariance, ClosedForm(J, s2)), 1e-10);
  EXPECT_LT((u.std - u.covariance.diagonal().cwiseSqrt()).norm(), 1e-15);
}

TEST(ComputeUncertainty, WeightedResidualsWithinTheirSigmasDoNotShrinkTheCovariance) {
  const ParameterVector p = Parameters();
  const Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 3);
  const Eigen::VectorXd r = 0.1 * ResidualAtSolution(J, 4);  // chi2/dof well below 1
  const Uncertainty u = ComputeUncertainty(p, r, J, /*weighted=*/true);
  ASSERT_TRUE(u.ok);
  ASSERT_LT(u.chi2_per_dof, 1.0);
  EXPECT_EQ(u.sigma2, 1.0);
  EXPECT_LT(RelativeError(u.covariance, ClosedForm(J, 1.0)), 1e-10);
}

TEST(ComputeUncertainty, WeightedMisfitBeyondTheSigmasGrowsTheCovariance) {
  const ParameterVector p = Parameters();
  const Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 5);
  const Eigen::VectorXd r = 10.0 * ResidualAtSolution(J, 6);
  const Uncertainty u = ComputeUncertainty(p, r, J, /*weighted=*/true);
  ASSERT_TRUE(u.ok);
  ASSERT_GT(u.chi2_per_dof, 1.0);
  EXPECT_DOUBLE_EQ(u.sigma2, u.chi2_per_dof);
  EXPECT_LT(RelativeError(u.covariance, ClosedForm(J, u.chi2_per_dof)), 1e-10);
}

TEST(ComputeUncertainty, ColumnsEightOrdersApartStillGiveTheClosedForm) {
  const ParameterVector p = Parameters();
  Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 7);
  // Half the columns tiny, and two of them nearly parallel: ill-conditioned before scaling
  // and beyond the Gram matrix's reach after it, so the SVD path answers.
  for (int j = 0; j < p.size(); j += 2) J.col(j) *= 1e-8;
  J.col(3) = J.col(1) + 1e-5 * RandomJacobian(kResiduals, 1, 70);
  const Eigen::VectorXd r = ResidualAtSolution(J, 8);
  const Uncertainty u = ComputeUncertainty(p, r, J, /*weighted=*/false);
  ASSERT_TRUE(u.ok);
  const double s2 = r.squaredNorm() / (kResiduals - p.size());
  // The reference in scaled coordinates, where the inverse is well defined.
  const Eigen::VectorXd d = J.colwise().norm();
  const Eigen::MatrixXd J_s = J * d.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd reference =
      d.cwiseInverse().asDiagonal() * ClosedForm(J_s, s2) * d.cwiseInverse().asDiagonal();
  EXPECT_LT(RelativeError(u.covariance, reference), 1e-6);
  EXPECT_GT(u.condition_number, 1e4);
}

TEST(ComputeUncertainty, OnlyTheFreeParametersHaveACovariance) {
  ParameterVector p = Parameters();
  p.Fix(0, "test");
  p.Fix(p.size() - 1, "test");
  const Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 9);
  const Eigen::VectorXd r = ResidualAtSolution(J, 10);
  const Uncertainty u = ComputeUncertainty(p, r, J, /*weighted=*/false);
  ASSERT_TRUE(u.ok);
  ASSERT_EQ(u.free_indices.size(), static_cast<size_t>(p.size() - 2));
  EXPECT_EQ(u.free_indices.front(), 1);
  const Eigen::MatrixXd J_free = J.middleCols(1, p.size() - 2);
  // The residual is not at the free-parameter solution, but the formula only needs r.
  const double s2 = r.squaredNorm() / (kResiduals - (p.size() - 2));
  EXPECT_LT(RelativeError(u.covariance, ClosedForm(J_free, s2)), 1e-10);
}

TEST(ComputeUncertainty, ARankDeficientJacobianHasNoCovariance) {
  const ParameterVector p = Parameters();
  Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 11);
  J.col(4) = 2.0 * J.col(2);  // two parameters that only act together
  const Uncertainty u = ComputeUncertainty(p, ResidualAtSolution(J, 12), J, false);
  EXPECT_FALSE(u.ok);
}

TEST(ComputeUncertainty, TooFewResidualsHaveNoCovariance) {
  const ParameterVector p = Parameters();
  const Eigen::MatrixXd J = RandomJacobian(p.size(), p.size(), 13);
  EXPECT_FALSE(ComputeUncertainty(p, Eigen::VectorXd::Ones(p.size()), J, false).ok);
}

TEST(ComputeUncertainty, NamesTheStronglyCorrelatedPair) {
  const ParameterVector p = Parameters();
  Eigen::MatrixXd J = RandomJacobian(kResiduals, p.size(), 14);
  J.col(6) = J.col(2) + 0.05 * RandomJacobian(kResiduals, 1, 140);
  const Uncertainty u = ComputeUncertainty(p, ResidualAtSolution(J, 15), J, false);
  ASSERT_TRUE(u.ok);
  ASSERT_EQ(u.correlations.size(), 1u);
  EXPECT_EQ(u.correlations[0].a, p.names()[2]);
  EXPECT_EQ(u.correlations[0].b, p.names()[6]);
  const double rho = u.covariance(2, 6) / (u.std[2] * u.std[6]);
  EXPECT_DOUBLE_EQ(u.correlations[0].correlation, rho);
  EXPECT_LT(rho, -0.9);  // columns alike: the estimates trade against each other
}

}  // namespace
}  // namespace h4::host

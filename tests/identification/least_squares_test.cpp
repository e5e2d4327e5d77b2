// The two minimisers of host/identification/least_squares.h on their own, on problems whose
// answer is known in closed form (Moré, Garbow and Hillstrom's test set): Rosenbrock's
// valley, Powell's singular function (its Jacobian is singular at the minimum), a
// rank-deficient Jacobian, and a residual that cannot be evaluated beyond a bound (a pose
// out of the robot's reach). The identification reaches them only through whole pipelines.
#include "host/identification/least_squares.h"

#include <cmath>

#include <Eigen/QR>
#include <gtest/gtest.h>

namespace h4::host {
namespace {

/// Rosenbrock: r = (10 (x2 - x1^2), 1 - x1), minimum 0 at (1, 1); start (-1.2, 1).
bool Rosenbrock(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  *r = Eigen::Vector2d(10.0 * (v[1] - v[0] * v[0]), 1.0 - v[0]);
  if (J) *J = (Eigen::Matrix2d() << -20.0 * v[0], 10.0, -1.0, 0.0).finished();
  return true;
}

/// Powell's singular function, minimum 0 at the origin, where J has rank 2; start (3,-1,0,1).
bool PowellSingular(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  const double s5 = std::sqrt(5.0), s10 = std::sqrt(10.0);
  const double a = v[1] - 2.0 * v[2], b = v[0] - v[3];
  *r = Eigen::Vector4d(v[0] + 10.0 * v[1], s5 * (v[2] - v[3]), a * a, s10 * b * b);
  if (J) {
    *J = Eigen::Matrix4d::Zero();
    (*J)(0, 0) = 1.0;
    (*J)(0, 1) = 10.0;
    (*J)(1, 2) = s5;
    (*J)(1, 3) = -s5;
    (*J)(2, 1) = 2.0 * a;
    (*J)(2, 2) = -4.0 * a;
    (*J)(3, 0) = 2.0 * s10 * b;
    (*J)(3, 3) = -2.0 * s10 * b;
  }
  return true;
}

/// Linear, r = A v - b with A's columns 1 and 2 equal and column 3 zero (a parameter with
/// no effect): rank 2 of 4, the least-squares cost 0 reachable.
bool RankDeficient(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  Eigen::MatrixXd A(3, 4);
  A << 1, 1, 0, 2,  //
      2, 2, 0, -1,  //
      -1, -1, 0, 1;
  *r = A * v - Eigen::Vector3d(1.0, 2.0, 3.0);
  if (J) *J = A;
  return true;
}

/// r = x - 2 with r undefined for x > 1.5: the best reachable point is the bound.
bool OutOfReachBeyond1p5(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  if (v[0] > 1.5) return false;
  *r = Eigen::VectorXd::Constant(1, v[0] - 2.0);
  if (J) *J = Eigen::MatrixXd::Ones(1, 1);
  return true;
}

double Cost(const ResidualFunction& f, const Eigen::VectorXd& v) {
  Eigen::VectorXd r;
  EXPECT_TRUE(f(v, &r, nullptr));
  return 0.5 * r.squaredNorm();
}

TEST(LevenbergMarquardt, FollowsRosenbrocksValleyToTheMinimum) {
  Eigen::VectorXd v = Eigen::Vector2d(-1.2, 1.0);
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(Rosenbrock, {}, &v);
  EXPECT_TRUE(report.converged) << report.stop_reason;
  EXPECT_NEAR(v[0], 1.0, 1e-8);
  EXPECT_NEAR(v[1], 1.0, 1e-8);
  EXPECT_DOUBLE_EQ(report.initial_cost, 12.1);  // 0.5 (4.4^2 + 2.2^2)
  EXPECT_LT(report.final_cost, 1e-20);
}

TEST(LevenbergMarquardt, ReachesPowellsSingularMinimumWhereTheJacobianLosesRank) {
  Eigen::VectorXd v = Eigen::Vector4d(3.0, -1.0, 0.0, 1.0);
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(PowellSingular, {}, &v);
  // Convergence is linear there (J is singular at the solution): close, not exact.
  EXPECT_LT(report.final_cost, 1e-12) << report.stop_reason;
  EXPECT_LT(v.norm(), 1e-3);
  EXPECT_TRUE(v.allFinite());
}

TEST(LevenbergMarquardt, ARankDeficientJacobianNeitherDivergesNorMovesTheIdleParameter) {
  Eigen::VectorXd v = Eigen::Vector4d(0.5, -0.5, 7.0, 0.0);
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(RankDeficient, {}, &v);
  EXPECT_TRUE(v.allFinite());
  EXPECT_DOUBLE_EQ(v[2], 7.0) << "a parameter with no effect must stay put";
  // The residual's part outside A's range stays: the minimum of the consistent problem.
  Eigen::MatrixXd A(3, 4);
  A << 1, 1, 0, 2, 2, 2, 0, -1, -1, -1, 0, 1;
  const Eigen::VectorXd b = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Eigen::VectorXd best = A.completeOrthogonalDecomposition().solve(b);
  EXPECT_NEAR(report.final_cost, 0.5 * (A * best - b).squaredNorm(), 1e-12);
}

TEST(LevenbergMarquardt, StaysWhereTheResidualCanBeEvaluated) {
  Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 0.0);
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(OutOfReachBeyond1p5, {}, &v);
  EXPECT_LE(v[0], 1.5);
  EXPECT_GT(v[0], 1.4) << "it should approach the bound, not stop at the first refusal";
  EXPECT_LT(report.final_cost, report.initial_cost);
}

TEST(LevenbergMarquardt, FailsCleanlyWhenTheStartCannotBeEvaluated) {
  Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 3.0);
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(OutOfReachBeyond1p5, {}, &v);
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.stop_reason.empty());
  EXPECT_EQ(v[0], 3.0);
}

TEST(LevenbergMarquardt, StopsWhenTheProgressCallbackSaysSo) {
  Eigen::VectorXd v = Eigen::Vector2d(-1.2, 1.0);
  int calls = 0;
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(
      Rosenbrock, {}, &v, [&calls](const std::string&, int, double) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  EXPECT_FALSE(report.converged);
  EXPECT_LE(report.iterations, 3);
}

TEST(Nlopt, LbfgsBringsRosenbrockDownAndNeverReturnsWorseThanTheStart) {
  Eigen::VectorXd v = Eigen::Vector2d(-1.2, 1.0);
  NloptOptions options;
  options.max_evaluations = 2000;
  options.relative_cost_tolerance = 1e-12;
  const MinimizerReport report = MinimizeWithNlopt(Rosenbrock, options, &v);
  EXPECT_LT(report.final_cost, 1e-6) << report.stop_reason;
  EXPECT_NEAR(Cost(Rosenbrock, v), report.final_cost, 1e-15);
  EXPECT_LE(report.evaluations, 2000);
}

TEST(Nlopt, ADerivativeFreeAlgorithmByNameWorksToo) {
  Eigen::VectorXd v = Eigen::Vector4d(3.0, -1.0, 0.0, 1.0);
  NloptOptions options;
  options.algorithm = "LN_BOBYQA";
  options.max_evaluations = 500;
  options.relative_cost_tolerance = 1e-12;  // the default (0.1) only aims at LM's basin
  const MinimizerReport report = MinimizeWithNlopt(PowellSingular, options, &v);
  EXPECT_EQ(report.name, "nlopt LN_BOBYQA");
  EXPECT_LT(report.final_cost, 1e-3 * report.initial_cost);
}

TEST(Nlopt, FewEvaluationsStillGiveAPointNoWorseThanTheStart) {
  Eigen::VectorXd v = Eigen::Vector2d(-1.2, 1.0);
  NloptOptions options;
  options.max_evaluations = 3;
  const MinimizerReport report = MinimizeWithNlopt(Rosenbrock, options, &v);
  EXPECT_LE(report.final_cost, report.initial_cost);
  EXPECT_LE(Cost(Rosenbrock, v), 12.1);
}

TEST(Nlopt, AnUnknownAlgorithmOrAnUnreachableStartFailsCleanly) {
  Eigen::VectorXd v = Eigen::Vector2d(-1.2, 1.0);
  NloptOptions options;
  options.algorithm = "LD_NO_SUCH";
  MinimizerReport report = MinimizeWithNlopt(Rosenbrock, options, &v);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(v, Eigen::Vector2d(-1.2, 1.0));
  std::string why;
  EXPECT_FALSE(IsValidNloptAlgorithm("LD_NO_SUCH", &why));
  EXPECT_NE(why.find("LD_LBFGS"), std::string::npos) << why;

  Eigen::VectorXd beyond = Eigen::VectorXd::Constant(1, 3.0);
  report = MinimizeWithNlopt(OutOfReachBeyond1p5, NloptOptions{}, &beyond);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(beyond[0], 3.0);
}

TEST(Nlopt, AnUnreachableTrialPointIsAvoidedNotReturned) {
  Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 0.0);
  NloptOptions options;
  options.max_evaluations = 200;
  options.relative_cost_tolerance = 1e-12;
  const MinimizerReport report = MinimizeWithNlopt(OutOfReachBeyond1p5, options, &v);
  EXPECT_LE(v[0], 1.5);
  EXPECT_LT(report.final_cost, report.initial_cost);
}

TEST(ColumnScale, IsTheColumnNormWithOneForAnIdleColumn) {
  Eigen::MatrixXd J(2, 3);
  J << 3, 0, 1, 4, 0, 0;
  EXPECT_EQ(ColumnScale(J), Eigen::Vector3d(5.0, 1.0, 1.0));
}

}  // namespace
}  // namespace h4::host

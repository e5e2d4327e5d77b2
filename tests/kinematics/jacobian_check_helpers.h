// The one shared check of analytic Jacobians: compares J_analytic with central finite
// differences of f at x0, entry by entry, and names the worst entries on failure. Every
// analytic Jacobian of the kinematics and identification tests is checked through it.
#pragma once

#include <functional>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "host/kinematics/kinematic_model.h"

namespace h4::host::testing {

/// A function R^n -> R^m whose Jacobian is checked. Outputs that are angles must be
/// continuous around x0 (wrap differences inside f, e.g. WrapAngle(q(x) - q(x0))).
using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

/// Central finite-difference Jacobian of f at x0: column j is
/// (f(x0 + step e_j) - f(x0 - step e_j)) / (2 step). Error O(step^2).
Eigen::MatrixXd FiniteDifferenceJacobian(const VectorFunction& f, const Eigen::VectorXd& x0,
                                         double step);

/// Success when J_analytic has the shape m x n of f at x0 and every entry satisfies
///   |J_analytic(i,j) - J_fd(i,j)| <= tolerance * max(1, |J_fd(i,j)|)
/// (absolute below 1, relative above), with J_fd = FiniteDifferenceJacobian(f, x0, step).
/// Typical use: step 1e-6, tolerance 1e-6 for metre/radian-scaled functions. On failure the
/// message lists the worst entries (row, column, analytic, numeric) and any non-finite entry.
///   EXPECT_TRUE(JacobianMatchesFiniteDifferences(f, x0, J, 1e-6, 1e-6));
::testing::AssertionResult JacobianMatchesFiniteDifferences(const VectorFunction& f,
                                                            const Eigen::VectorXd& x0,
                                                            const Eigen::MatrixXd& J_analytic,
                                                            double step, double tolerance);

/// The three Jacobians of a model's closure constraints f(q, x, xi) (ConstraintJacobians:
/// by x, by q, by the parameters xi) against finite differences at (q, x), step 1e-6,
/// tolerance 1e-8; a failure names which Jacobian.
::testing::AssertionResult ConstraintJacobiansMatchFiniteDifferences(const KinematicModel& model,
                                                                     const JointVector& q,
                                                                     const EePose& x);

}  // namespace h4::host::testing

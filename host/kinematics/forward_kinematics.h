// Numerical forward kinematics of the H4 for either model: Newton's method on the four
// closure equations f(q, x) = 0 (paper eq. (1) / (4)) with the analytic J_f_x, and the
// derivatives of the resulting pose by the joints and the parameters (implicit function
// theorem), which the measurement-space identification needs.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// Named by ToString, in this order (forward_kinematics.cpp).
enum class FkStatus {
  kConverged,     ///< f(q, x) = 0 within tolerance and IK(x) reproduces q (same branch)
  kNotConverged,  ///< iteration limit or stalled line search: likely no pose for these joints
  kSingular,      ///< J_f_x singular at an iterate (and damping did not help)
  kWrongBranch,   ///< converged to a pose whose IK (assembly eps) gives other joints
  kInvalidInput,  ///< non-finite joints or initial guess
};

/// "converged", "not converged", "singular", "wrong branch", "invalid input".
const char* ToString(FkStatus status);

struct FkOptions {
  int max_iterations = 50;            ///< Newton iterations per start
  double residual_tolerance = 1e-12;  ///< converged when max_i |f_i| is below, m^2
  double max_step = 0.1;              ///< a Newton step longer than this is scaled down, m|rad
  double branch_tolerance = 1e-6;     ///< IK(x) must reproduce q within this (wrapped), rad
  /// When the given initial guess fails, also try the model's workspace centre.
  bool retry_from_centre = true;
};

struct FkResult {
  FkStatus status = FkStatus::kInvalidInput;
  /// The pose in the model's base frame (m, rad); the last iterate (finite) when not ok().
  EePose x = EePose::Zero();
  int iterations = 0;     ///< Newton iterations over all starts
  double residual = 0.0;  ///< max_i |f_i| at x, m^2
  std::string message;    ///< why it failed (empty on success)
  bool ok() const { return status == FkStatus::kConverged; }
};

/// Solves f(q, x) = 0 for x, from `initial_guess` or else model.WorkspaceCentre(). Never
/// throws and never returns NaN; allocation-free on success.
FkResult ForwardKinematics(const KinematicModel& model, const JointVector& q,
                           const std::optional<EePose>& initial_guess = std::nullopt,
                           const FkOptions& options = FkOptions{});

/// The derivatives of the forward kinematic pose at a consistent (q, x) (f(q, x) = 0):
/// J_x_q = -J_f_x^-1 diag(J_f_q) (4x4) and J_x_xi = -J_f_x^-1 J_f_xi (4 x parameter count).
/// Null outputs are skipped. Returns false (outputs untouched) when J_f_x is singular.
bool ForwardKinematicsJacobians(const KinematicModel& model, const JointVector& q, const EePose& x,
                                Eigen::Matrix4d* J_x_q, Eigen::MatrixXd* J_x_xi);

}  // namespace h4::host

// The interface both H4 kinematic models implement (common/README.md): Model 12, the
// design model (paper eq. (1)-(2)), and Model 31, the calibration model (eq. (4)).
// Identification, simulation and validation are written against this interface only.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/kinematics/model_kind.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// End-effector pose (X, Y, Z, theta): X_BE = (Rz(theta), [X, Y, Z]) in the model's
/// base frame (B for Model 12, B31 for Model 31), m and rad.
using EePose = Eigen::Vector4d;
/// Joint readings q1..q4 (encoder values, rad; the geometric angle is q_i + q0_i).
using JointVector = Eigen::Vector4d;

/// Result of the closed-form inverse kinematics: per leg, either an angle or
/// "unreachable" (|G| > sqrt(M^2 + N^2)). Never NaN: unreachable legs hold 0.
struct IkResult {
  JointVector q = JointVector::Zero();
  std::array<bool, 4> reachable{false, false, false, false};
  bool ok() const { return reachable[0] && reachable[1] && reachable[2] && reachable[3]; }
  /// The 1-based numbers of the legs without a solution, as "1, 3" (empty when all reach).
  std::string UnreachableLegNumbers() const;
};

class KinematicModel {
 public:
  virtual ~KinematicModel() = default;

  /// Model 12 or Model 31.
  virtual ModelKind kind() const = 0;
  /// common/README.md names, in the order of parameters(): Model 12: h, arm, forearm, R, d,
  /// alpha1..alpha4, q01..q04 (13, d inert); Model 31: x2 y2 z2 x3 y3 z3 x4 y4 z4,
  /// psi1..psi4, beta1..beta4, q01..q04, arm1..arm4, forearm1..forearm4, h, d (31).
  virtual const std::vector<std::string>& parameter_names() const = 0;
  virtual Eigen::VectorXd parameters() const = 0;
  virtual void set_parameters(const Eigen::VectorXd& xi) = 0;
  virtual std::unique_ptr<KinematicModel> Clone() const = 0;
  virtual const Assembly& assembly() const = 0;

  /// The centre of the paper's workspace in the model's base frame, theta = 0: the default
  /// starting guess of forward kinematics (Model 12: (0, 0, -0.45, 0) in B; Model 31: the
  /// same point expressed in B31).
  virtual EePose WorkspaceCentre() const = 0;

  /// Closed-form inverse kinematics per leg (eq. (2), atan2 form; common/README.md).
  virtual IkResult InverseKinematics(const EePose& x) const = 0;

  /// Implicit closure equations, one per leg, f_i = |closing vector|^2 - forearm_i^2
  /// (m^2): zero when joints q and pose x are consistent (eq. (1) / eq. (4)).
  virtual Eigen::Vector4d Constraints(const JointVector& q, const EePose& x) const = 0;

  /// Analytic Jacobians of Constraints at (q, x): J_f_x (4x4) by the pose, the diagonal of
  /// J_f_q (each f_i depends on q_i only), and J_f_xi (4 x parameter count) by the
  /// parameters. Null outputs are skipped.
  virtual void ConstraintJacobians(const JointVector& q, const EePose& x, Eigen::Matrix4d* J_f_x,
                                   Eigen::Vector4d* J_f_q_diagonal,
                                   Eigen::MatrixXd* J_f_xi) const = 0;
};

}  // namespace h4::host

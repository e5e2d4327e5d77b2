// Model 31, the H4 calibration model (paper eq. (4),
// common/README.md#model-31-calibration-model-31-parameters): per-leg closed-form inverse
// kinematics, closure equations f_i = |arm_i V_i + W_i|^2 - forearm_i^2 and their analytic
// Jacobians; and the nominal map from Model 12's base B to B31.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

class Model31 final : public KinematicModel {
 public:
  static constexpr int kParameterCount = 31;

  explicit Model31(const Model31Parameters& parameters, const Assembly& assembly = Assembly{});

  /// x2 y2 z2 x3 y3 z3 x4 y4 z4, psi1..psi4, beta1..beta4, q01..q04, arm1..arm4,
  /// forearm1..forearm4, h, d.
  static const std::vector<std::string>& ParameterNames();
  static Eigen::VectorXd ToVector(const Model31Parameters& p);
  /// Precondition: xi.size() == 31 (throws std::invalid_argument otherwise).
  static Model31Parameters FromVector(const Eigen::VectorXd& xi);

  const Model31Parameters& model31_parameters() const { return p_; }

  ModelKind kind() const override { return ModelKind::k31; }
  const std::vector<std::string>& parameter_names() const override { return ParameterNames(); }
  Eigen::VectorXd parameters() const override { return ToVector(p_); }
  void set_parameters(const Eigen::VectorXd& xi) override;
  std::unique_ptr<KinematicModel> Clone() const override;
  const Assembly& assembly() const override { return assembly_; }
  /// The grid centre in B31: the least-squares nacelle point that sits at a common distance
  /// from every base joint along its axis azimuth psi_i (exact for a nominal Model 31:
  /// (R cos alpha1, R sin alpha1 - d, -0.45)), theta = 0.
  EePose WorkspaceCentre() const override { return centre_; }

  IkResult InverseKinematics(const EePose& x) const override;
  Eigen::Vector4d Constraints(const JointVector& q, const EePose& x) const override;
  void ConstraintJacobians(const JointVector& q, const EePose& x, Eigen::Matrix4d* J_f_x,
                           Eigen::Vector4d* J_f_q_diagonal, Eigen::MatrixXd* J_f_xi) const override;

  /// W_i = A_i - P_i in B31 for leg i (0-based).
  Eigen::Vector3d LegVector(int leg, const EePose& x) const;

 private:
  Eigen::Vector3d BaseJoint(int leg) const;
  void UpdateAxes();
  void UpdateCentre();

  /// Per leg: the axes a, b of the arm's rotation plane (V = sin(phi) a + cos(phi) b) and
  /// their derivatives by psi and beta, from the parameters (see UpdateAxes).
  struct LegAxes {
    Eigen::Vector3d a, b, a_psi, b_psi, a_beta;
  };
  std::array<LegAxes, 4> axes_{};
  Model31Parameters p_;
  Assembly assembly_;
  EePose centre_ = EePose::Zero();
};

/// The nominal X_B31B (common/README.md): B31 = B translated, so that a pose maps by
/// X31 = X12 + R cos alpha1, Y31 = Y12 + R sin alpha1 - d, Z31 = Z12 (theta unchanged).
/// Then X_B31C = X_B31B * X_BC, and NominalModel31(m12) at X_B31B * X_BE gives Model 12's joints.
RigidTransform NominalX_B31B(const Model12Parameters& m12);

/// The pose x_B (in B) expressed in B31 through X_B31B, which should rotate about z only;
/// theta is then theta_B plus that rotation.
EePose EePoseInB31(const EePose& x_B, const RigidTransform& X_B31B);

}  // namespace h4::host

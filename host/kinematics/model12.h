// Model 12, the H4 design model (paper eq. (1)-(2),
// common/README.md#model-12-design-model-12-parameters): closed-form inverse kinematics per leg,
// the closure equations f_i = |PA_i - arm u_i|^2 - forearm^2 and their analytic Jacobians by pose,
// joints and the 13 parameters.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

class Model12 final : public KinematicModel {
 public:
  static constexpr int kParameterCount = 13;

  explicit Model12(const Model12Parameters& parameters, const Assembly& assembly = Assembly{});

  /// h, arm, forearm, R, d, alpha1..alpha4, q01..q04.
  static const std::vector<std::string>& ParameterNames();
  static Eigen::VectorXd ToVector(const Model12Parameters& p);
  /// Precondition: xi.size() == 13 (throws std::invalid_argument otherwise).
  static Model12Parameters FromVector(const Eigen::VectorXd& xi);

  const Model12Parameters& model12_parameters() const { return p_; }

  ModelKind kind() const override { return ModelKind::k12; }
  const std::vector<std::string>& parameter_names() const override { return ParameterNames(); }
  Eigen::VectorXd parameters() const override { return ToVector(p_); }
  void set_parameters(const Eigen::VectorXd& xi) override { p_ = FromVector(xi); }
  std::unique_ptr<KinematicModel> Clone() const override;
  const Assembly& assembly() const override { return assembly_; }
  EePose WorkspaceCentre() const override;

  IkResult InverseKinematics(const EePose& x) const override;
  Eigen::Vector4d Constraints(const JointVector& q, const EePose& x) const override;
  void ConstraintJacobians(const JointVector& q, const EePose& x, Eigen::Matrix4d* J_f_x,
                           Eigen::Vector4d* J_f_q_diagonal, Eigen::MatrixXd* J_f_xi) const override;

  /// PA_i, the vector from base joint P_i to nacelle joint A_i in B, for leg i (0-based).
  Eigen::Vector3d LegVector(int leg, const EePose& x) const;

 private:
  Model12Parameters p_;
  Assembly assembly_;
};

}  // namespace h4::host

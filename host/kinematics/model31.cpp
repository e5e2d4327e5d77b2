// Model 31 (paper eq. (4)); see model31.h. With c_i = arm_i V_i + W_i and
// f_i = |c_i|^2 - forearm_i^2, every derivative is df = 2 c_i . dc_i.
#include "host/kinematics/model31.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/leg_angle.h"
#include "host/kinematics/leg_closure.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model_parameters.h"

namespace h4::host {
namespace {

// Parameter indices in the common/README.md order.
constexpr int kP = 0, kPsi = 9, kBeta = 13, kQ0 = 17, kArm = 21, kForearm = 25, kH = 29, kD = 30;

constexpr double kCentreZ = -0.45;  // grid centre depth below the base joints, m

// V = sin(phi) a + cos(phi) b (common/README.md), a and b orthonormal.
Eigen::Vector3d AxisA(double psi, double beta) {
  return {std::cos(beta) * std::sin(psi), -std::cos(beta) * std::cos(psi), -std::sin(beta)};
}
Eigen::Vector3d AxisB(double psi) { return {-std::cos(psi), -std::sin(psi), 0.0}; }

}  // namespace

Model31::Model31(const Model31Parameters& parameters, const Assembly& assembly)
    : p_(parameters), assembly_(assembly) {
  UpdateAxes();
  UpdateCentre();
}

const std::vector<std::string>& Model31::ParameterNames() {
  static const std::vector<std::string> names = ParameterNamesOf(Model31ParameterTable());
  return names;
}

Eigen::VectorXd Model31::ToVector(const Model31Parameters& p) {
  Eigen::VectorXd xi(kParameterCount);
  for (int j = 0; j < 3; ++j) xi.segment<3>(kP + 3 * j) = p.P[static_cast<size_t>(j)];
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<size_t>(i);
    xi[kPsi + i] = p.psi[k];
    xi[kBeta + i] = p.beta[k];
    xi[kQ0 + i] = p.q0[k];
    xi[kArm + i] = p.arm[k];
    xi[kForearm + i] = p.forearm[k];
  }
  xi[kH] = p.h;
  xi[kD] = p.d;
  return xi;
}

Model31Parameters Model31::FromVector(const Eigen::VectorXd& xi) {
  if (xi.size() != kParameterCount) {
    throw std::invalid_argument(fmt::format("Model 31 expects 31 parameters, got {}", xi.size()));
  }
  Model31Parameters p;
  for (int j = 0; j < 3; ++j) p.P[static_cast<size_t>(j)] = xi.segment<3>(kP + 3 * j);
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<size_t>(i);
    p.psi[k] = xi[kPsi + i];
    p.beta[k] = xi[kBeta + i];
    p.q0[k] = xi[kQ0 + i];
    p.arm[k] = xi[kArm + i];
    p.forearm[k] = xi[kForearm + i];
  }
  p.h = xi[kH];
  p.d = xi[kD];
  return p;
}

void Model31::set_parameters(const Eigen::VectorXd& xi) {
  p_ = FromVector(xi);
  UpdateAxes();
  UpdateCentre();
}

std::unique_ptr<KinematicModel> Model31::Clone() const { return std::make_unique<Model31>(*this); }

void Model31::UpdateAxes() {
  // The axes depend on the parameters only: computed once per parameter set, not on every
  // constraint evaluation (the identification evaluates thousands per parameter set).
  for (size_t i = 0; i < 4; ++i) {
    const double psi = p_.psi[i], beta = p_.beta[i];
    LegAxes& axes = axes_[i];
    axes.a = AxisA(psi, beta);
    axes.b = AxisB(psi);
    axes.a_psi = {std::cos(beta) * std::cos(psi), std::cos(beta) * std::sin(psi), 0.0};
    axes.b_psi = {std::sin(psi), -std::cos(psi), 0.0};
    axes.a_beta = {-std::sin(beta) * std::sin(psi), std::sin(beta) * std::cos(psi),
                   -std::cos(beta)};
  }
}

void Model31::UpdateCentre() {
  // Unknowns (X, Y, R): X - R cos psi_i = x_i and Y + d - R sin psi_i = y_i for every leg,
  // which the nominal model satisfies exactly with Model 12's R.
  Eigen::Matrix<double, 8, 3> A;
  Eigen::Matrix<double, 8, 1> b;
  double mean_z = 0.0;
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const Eigen::Vector3d P = BaseJoint(leg);
    A.row(2 * leg) << 1.0, 0.0, -std::cos(p_.psi[i]);
    A.row(2 * leg + 1) << 0.0, 1.0, -std::sin(p_.psi[i]);
    b[2 * leg] = P.x();
    b[2 * leg + 1] = P.y() - p_.d;
    mean_z += P.z() / 4.0;
  }
  const Eigen::Vector3d solution = A.colPivHouseholderQr().solve(b);
  if (solution.allFinite()) {
    centre_ = EePose(solution[0], solution[1], kCentreZ + mean_z, 0.0);
  } else {
    centre_ = EePose(0.0, -p_.d, kCentreZ + mean_z, 0.0);
  }
}

Eigen::Vector3d Model31::BaseJoint(int leg) const {
  return leg == 0 ? Eigen::Vector3d::Zero() : p_.P[static_cast<size_t>(leg - 1)];
}

Eigen::Vector3d Model31::LegVector(int leg, const EePose& x) const {
  const double s = assembly_.bar[static_cast<size_t>(leg)];
  const double theta = x[3];
  const Eigen::Vector3d A(x[0] + s * p_.h * (std::cos(theta) - 1.0),
                          x[1] + s * p_.h * std::sin(theta) + p_.d, x[2]);
  return A - BaseJoint(leg);
}

IkResult Model31::InverseKinematics(const EePose& x) const {
  return SolveLegs(x, assembly_, p_.q0, [this, &x](int leg) {
    const auto i = static_cast<size_t>(leg);
    const Eigen::Vector3d W = LegVector(leg, x);
    // |arm V + W|^2 = forearm^2 with V = sin(phi) a + cos(phi) b:
    // 2 arm (b.W) cos(phi) + 2 arm (a.W) sin(phi) = forearm^2 - arm^2 - |W|^2.
    return LegEquation{
        .M = 2.0 * p_.arm[i] * axes_[i].b.dot(W),
        .N = 2.0 * p_.arm[i] * axes_[i].a.dot(W),
        .G = p_.forearm[i] * p_.forearm[i] - p_.arm[i] * p_.arm[i] - W.squaredNorm()};
  });
}

Eigen::Vector4d Model31::Constraints(const JointVector& q, const EePose& x) const {
  Eigen::Vector4d f;
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const double phi = q[leg] + p_.q0[i];
    const Eigen::Vector3d V = std::sin(phi) * axes_[i].a + std::cos(phi) * axes_[i].b;
    f[leg] = (p_.arm[i] * V + LegVector(leg, x)).squaredNorm() - p_.forearm[i] * p_.forearm[i];
  }
  return f;
}

void Model31::ConstraintJacobians(const JointVector& q, const EePose& x, Eigen::Matrix4d* J_f_x,
                                  Eigen::Vector4d* J_f_q_diagonal, Eigen::MatrixXd* J_f_xi) const {
  if (J_f_xi != nullptr) J_f_xi->setZero(4, kParameterCount);
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const double arm = p_.arm[i];
    const LegAxes& axes = axes_[i];
    const double phi = q[leg] + p_.q0[i];
    const double sp = std::sin(phi), cp = std::cos(phi);
    const Eigen::Vector3d& a = axes.a;
    const Eigen::Vector3d& b = axes.b;
    const Eigen::Vector3d V = sp * a + cp * b;
    const Eigen::Vector3d c = arm * V + LegVector(leg, x);
    const double f_phi = 2.0 * arm * c.dot(cp * a - sp * b);
    SetClosureByPose(leg, c, assembly_.bar[i], p_.h, x[3], J_f_x);
    if (J_f_q_diagonal != nullptr) (*J_f_q_diagonal)[leg] = f_phi;
    if (J_f_xi == nullptr) continue;
    auto row = J_f_xi->row(leg);
    if (leg > 0) row.segment<3>(kP + 3 * (leg - 1)) = -2.0 * c;  // W = A - P_i
    row[kPsi + leg] = 2.0 * arm * c.dot(sp * axes.a_psi + cp * axes.b_psi);
    row[kBeta + leg] = 2.0 * arm * sp * c.dot(axes.a_beta);
    row[kQ0 + leg] = f_phi;
    row[kArm + leg] = 2.0 * c.dot(V);
    row[kForearm + leg] = -2.0 * p_.forearm[i];
    row[kH] = ClosureByH(c, assembly_.bar[i], x[3]);
    row[kD] = 2.0 * c.y();
  }
}

RigidTransform NominalX_B31B(const Model12Parameters& m12) {
  return RigidTransform(
      Eigen::Matrix3d::Identity(),
      Eigen::Vector3d(m12.R * std::cos(m12.alpha[0]), m12.R * std::sin(m12.alpha[0]) - m12.d, 0.0));
}

EePose EePoseInB31(const EePose& x_B, const RigidTransform& X_B31B) {
  return EePoseFromTransform(X_B31B * TransformFromEePose(x_B));
}

}  // namespace h4::host

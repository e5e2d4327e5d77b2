// Model 12 (paper eq. (1)-(2)); see model12.h. The derivatives below follow from
// f_i = |c_i|^2 - forearm^2 with c_i = PA_i - arm u_i, so df = 2 c_i . dc_i.
#include "host/kinematics/model12.h"

#include <cmath>
#include <stdexcept>

#include <fmt/core.h>

#include "common/geometry/rotation.h"
#include "host/kinematics/leg_angle.h"
#include "host/kinematics/leg_closure.h"
#include "host/kinematics/model_parameters.h"

namespace h4::host {
namespace {

// Parameter indices in the common/README.md order.
constexpr int kH = 0, kArm = 1, kForearm = 2, kR = 3, kD = 4, kAlpha = 5, kQ0 = 9;

// Workspace centre of the paper's pose grid, in B (common/README.md#checks-against-the-paper).
constexpr double kCentreZ = -0.45;

// Arm direction u_i for the geometric angle phi and its derivatives by phi and alpha.
Eigen::Vector3d ArmDirection(double alpha, double phi) {
  return {std::cos(alpha) * std::cos(phi), std::sin(alpha) * std::cos(phi), -std::sin(phi)};
}
Eigen::Vector3d ArmDirectionByPhi(double alpha, double phi) {
  return {-std::cos(alpha) * std::sin(phi), -std::sin(alpha) * std::sin(phi), -std::cos(phi)};
}

}  // namespace

Model12::Model12(const Model12Parameters& parameters, const Assembly& assembly)
    : p_(parameters), assembly_(assembly) {}

const std::vector<std::string>& Model12::ParameterNames() {
  static const std::vector<std::string> names = ParameterNamesOf(Model12ParameterTable());
  return names;
}

Eigen::VectorXd Model12::ToVector(const Model12Parameters& p) {
  Eigen::VectorXd xi(kParameterCount);
  xi[kH] = p.h;
  xi[kArm] = p.arm;
  xi[kForearm] = p.forearm;
  xi[kR] = p.R;
  xi[kD] = p.d;
  for (int i = 0; i < 4; ++i) {
    xi[kAlpha + i] = p.alpha[static_cast<size_t>(i)];
    xi[kQ0 + i] = p.q0[static_cast<size_t>(i)];
  }
  return xi;
}

Model12Parameters Model12::FromVector(const Eigen::VectorXd& xi) {
  if (xi.size() != kParameterCount) {
    throw std::invalid_argument(fmt::format("Model 12 expects 13 parameters, got {}", xi.size()));
  }
  Model12Parameters p;
  p.h = xi[kH];
  p.arm = xi[kArm];
  p.forearm = xi[kForearm];
  p.R = xi[kR];
  p.d = xi[kD];
  for (int i = 0; i < 4; ++i) {
    p.alpha[static_cast<size_t>(i)] = xi[kAlpha + i];
    p.q0[static_cast<size_t>(i)] = xi[kQ0 + i];
  }
  return p;
}

std::unique_ptr<KinematicModel> Model12::Clone() const { return std::make_unique<Model12>(*this); }

EePose Model12::WorkspaceCentre() const { return EePose(0.0, 0.0, kCentreZ, 0.0); }

Eigen::Vector3d Model12::LegVector(int leg, const EePose& x) const {
  const auto i = static_cast<size_t>(leg);
  const double s = assembly_.bar[i];
  const double theta = x[3];
  return {x[0] + s * p_.h * (std::cos(theta) - 1.0) + p_.R * std::cos(p_.alpha[i]),
          x[1] + s * p_.h * std::sin(theta) + p_.R * std::sin(p_.alpha[i]), x[2]};
}

IkResult Model12::InverseKinematics(const EePose& x) const {
  return SolveLegs(x, assembly_, p_.q0, [this, &x](int leg) {
    const auto i = static_cast<size_t>(leg);
    const Eigen::Vector3d PA = LegVector(leg, x);
    return LegEquation{
        .M = -2.0 * p_.arm * (PA.x() * std::cos(p_.alpha[i]) + PA.y() * std::sin(p_.alpha[i])),
        .N = 2.0 * p_.arm * PA.z(),
        .G = p_.forearm * p_.forearm - p_.arm * p_.arm - PA.squaredNorm()};
  });
}

Eigen::Vector4d Model12::Constraints(const JointVector& q, const EePose& x) const {
  Eigen::Vector4d f;
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const Eigen::Vector3d c =
        LegVector(leg, x) - p_.arm * ArmDirection(p_.alpha[i], q[leg] + p_.q0[i]);
    f[leg] = c.squaredNorm() - p_.forearm * p_.forearm;
  }
  return f;
}

void Model12::ConstraintJacobians(const JointVector& q, const EePose& x, Eigen::Matrix4d* J_f_x,
                                  Eigen::Vector4d* J_f_q_diagonal, Eigen::MatrixXd* J_f_xi) const {
  if (J_f_xi != nullptr) J_f_xi->setZero(4, kParameterCount);
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const double alpha = p_.alpha[i];
    const double phi = q[leg] + p_.q0[i];
    const Eigen::Vector3d u = ArmDirection(alpha, phi);
    const Eigen::Vector3d c = LegVector(leg, x) - p_.arm * u;
    const double f_phi = -2.0 * p_.arm * c.dot(ArmDirectionByPhi(alpha, phi));
    SetClosureByPose(leg, c, assembly_.bar[i], p_.h, x[3], J_f_x);
    if (J_f_q_diagonal != nullptr) (*J_f_q_diagonal)[leg] = f_phi;
    if (J_f_xi != nullptr) {
      auto row = J_f_xi->row(leg);
      row[kH] = ClosureByH(c, assembly_.bar[i], x[3]);
      row[kArm] = -2.0 * c.dot(u);
      row[kForearm] = -2.0 * p_.forearm;
      row[kR] = 2.0 * (c.x() * std::cos(alpha) + c.y() * std::sin(alpha));
      // row[kD] stays 0: d has no influence on Model 12.
      const Eigen::Vector3d c_alpha(
          -p_.R * std::sin(alpha) + p_.arm * std::sin(alpha) * std::cos(phi),
          p_.R * std::cos(alpha) - p_.arm * std::cos(alpha) * std::cos(phi), 0.0);
      row[kAlpha + leg] = 2.0 * c.dot(c_alpha);
      row[kQ0 + leg] = f_phi;
    }
  }
}

}  // namespace h4::host

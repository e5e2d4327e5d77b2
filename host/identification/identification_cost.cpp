// The identification costs, eq. (3), eq. (5) and measurement space; see
// identification_cost.h. Derivatives of q (IK) and x (FK) by the parameters come from
// f(q, x, xi) = 0: dq_i = -(J_f_x dx + J_f_xi dxi)_i / J_f_q_i and dx = -J_f_x^-1 J_f_xi dxi.
#include "host/identification/identification_cost.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>
#include <fmt/core.h>

#include "common/geometry/rotation.h"
#include "common/text/enum_names.h"
#include "host/identification/pose_chain.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {
namespace {

std::string PoseName(const DatasetRow& row) { return fmt::format("pose {}", row.pose_id); }

}  // namespace

const char* ToString(CostKind kind) { return kCostKindNames.NameOf(kind, "unknown"); }

std::optional<CostKind> ParseCostKind(const std::string& text) {
  return kCostKindNames.ValueNamed(text);
}

IdentificationCost::IdentificationCost(CostKind kind, const KinematicModel& model,
                                       std::vector<DatasetRow> rows, const CostOptions& options)
    : kind_(kind),
      model_(model.Clone()),
      rows_(std::move(rows)),
      options_(options),
      fk_(rows_.size()) {
  const std::vector<std::string>& names = model_->parameter_names();
  for (int leg = 0; leg < 4; ++leg) {
    int index = -1;
    for (size_t k = 0; k < names.size(); ++k) {
      if (names[k] == "forearm" || names[k] == fmt::format("forearm{}", leg + 1)) {
        index = static_cast<int>(k);
      }
    }
    if (index < 0) throw std::invalid_argument("IdentificationCost: model has no forearm length");
    forearm_index_.push_back(index);
  }
}

IdentificationCost::IdentificationCost(const IdentificationCost& other)
    : kind_(other.kind_),
      model_(other.model_->Clone()),
      rows_(other.rows_),
      options_(other.options_),
      forearm_index_(other.forearm_index_),
      fk_(other.fk_) {}

double IdentificationCost::RotationWeight(const DatasetRow& row) const {
  const double s = options_.use_dataset_sigmas && row.sigma_r && *row.sigma_r > 0
                       ? *row.sigma_r
                       : options_.default_sigma_r;
  return 1.0 / s;
}

double IdentificationCost::TranslationWeight(const DatasetRow& row) const {
  const double s = options_.use_dataset_sigmas && row.sigma_t && *row.sigma_t > 0
                       ? *row.sigma_t
                       : options_.default_sigma_t;
  return 1.0 / s;
}

bool IdentificationCost::Evaluate(const ParameterVector& p, Eigen::VectorXd* r, Eigen::MatrixXd* J,
                                  std::string* why) {
  p.ApplyTo(model_.get());
  const int m = residuals_per_pose();
  const ChainTransforms chain = MakeChainTransforms(p.X_BC(), p.X_TE());
  r->resize(residual_count());
  // Every entry of J is written below (kinematic columns, X_BC, X_TE for every row).
  if (J != nullptr) J->resize(residual_count(), p.size());
  for (size_t j = 0; j < rows_.size(); ++j) {
    const Eigen::Index row0 = static_cast<Eigen::Index>(j) * m;
    auto r_j = r->segment(row0, m);
    bool ok = false;
    switch (kind_) {
      case CostKind::kJointSpace:
        ok = EvaluateJoint(p, chain, rows_[j], r_j, J, row0, why);
        break;
      case CostKind::kImplicit:
        ok = EvaluateImplicit(p, chain, rows_[j], r_j, J, row0, why);
        break;
      case CostKind::kMeasurement:
        ok = EvaluateMeasurement(p, chain, j, r_j, J, row0, why);
        break;
    }
    if (!ok) return false;
  }
  if (!r->allFinite() || (J != nullptr && !J->allFinite())) {
    if (why != nullptr) *why = "non-finite residual or Jacobian";
    return false;
  }
  return true;
}

bool IdentificationCost::EvaluateJoint(const ParameterVector& p,
                                       const ChainTransforms& chain_transforms,
                                       const DatasetRow& row, Eigen::Ref<Eigen::VectorXd> r,
                                       Eigen::MatrixXd* J, Eigen::Index row0, std::string* why) {
  const MeasuredEePoseJacobians chain =
      EePoseFromMeasurementWithJacobians(chain_transforms, row.X_CT);
  const IkResult ik = model_->InverseKinematics(chain.x);
  if (!ik.ok()) {
    if (why != nullptr) *why = PoseName(row) + " is out of reach of the model (IK)";
    return false;
  }
  for (int i = 0; i < 4; ++i) r[i] = WrapAngle(ik.q[i] - row.q[static_cast<size_t>(i)]);
  if (J == nullptr) return true;
  Eigen::Matrix4d J_f_x;
  Eigen::Vector4d J_f_q;
  Eigen::MatrixXd& J_f_xi = J_f_xi_;
  model_->ConstraintJacobians(ik.q, chain.x, &J_f_x, &J_f_q, &J_f_xi);
  const int n_kin = p.kinematic_count();
  for (int i = 0; i < 4; ++i) {
    if (std::abs(J_f_q[i]) < 1e-12) {
      if (why != nullptr) *why = fmt::format("{}: leg {} singular", PoseName(row), i + 1);
      return false;
    }
    const double s = -1.0 / J_f_q[i];
    auto J_row = J->row(row0 + i);
    J_row.head(n_kin) = s * J_f_xi.row(i);
    J_row.segment<6>(p.bc_offset()) = s * J_f_x.row(i) * chain.J_x_bc;
    J_row.segment<6>(p.te_offset()) = s * J_f_x.row(i) * chain.J_x_te;
  }
  return true;
}

bool IdentificationCost::EvaluateImplicit(const ParameterVector& p,
                                          const ChainTransforms& chain_transforms,
                                          const DatasetRow& row, Eigen::Ref<Eigen::VectorXd> r,
                                          Eigen::MatrixXd* J, Eigen::Index row0, std::string* why) {
  (void)why;  // always evaluable: no IK, no FK
  const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
  const MeasuredEePoseJacobians chain =
      EePoseFromMeasurementWithJacobians(chain_transforms, row.X_CT);
  const Eigen::Vector4d f = model_->Constraints(q, chain.x);
  Eigen::Vector4d length;  // |closing vector_i| = sqrt(f_i + forearm_i^2)
  for (int i = 0; i < 4; ++i) {
    const double F = p.values()[forearm_index_[static_cast<size_t>(i)]];
    length[i] = std::sqrt(std::max(f[i] + F * F, 1e-24));
    r[i] = F - length[i];
  }
  if (J == nullptr) return true;
  Eigen::Matrix4d J_f_x;
  Eigen::MatrixXd& J_f_xi = J_f_xi_;
  model_->ConstraintJacobians(q, chain.x, &J_f_x, nullptr, &J_f_xi);
  const int n_kin = p.kinematic_count();
  for (int i = 0; i < 4; ++i) {
    const int k_F = forearm_index_[static_cast<size_t>(i)];
    const double F = p.values()[k_F];
    const double s = -0.5 / length[i];  // d(-|c|)/df
    auto J_row = J->row(row0 + i);
    J_row.head(n_kin) = s * J_f_xi.row(i);
    // |c|^2 = f + F^2, so F enters |c| directly besides through f.
    J_row[k_F] += 1.0 + s * 2.0 * F;
    J_row.segment<6>(p.bc_offset()) = s * J_f_x.row(i) * chain.J_x_bc;
    J_row.segment<6>(p.te_offset()) = s * J_f_x.row(i) * chain.J_x_te;
  }
  return true;
}

bool IdentificationCost::EvaluateMeasurement(const ParameterVector& p,
                                             const ChainTransforms& chain_transforms, size_t j,
                                             Eigen::Ref<Eigen::VectorXd> r, Eigen::MatrixXd* J,
                                             Eigen::Index row0, std::string* why) {
  const DatasetRow& row = rows_[j];
  const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
  const FkResult fk = fk_.Solve(*model_, j, row, chain_transforms.X_BC, chain_transforms.X_TE);
  if (!fk.ok()) {
    if (why != nullptr) *why = PoseName(row) + ": forward kinematics " + ToString(fk.status);
    return false;
  }
  const BoardPoseError err = BoardPoseErrorOf(chain_transforms, fk.x, row.X_CT, J != nullptr);
  const double w_r = RotationWeight(row);
  const double w_t = TranslationWeight(row);
  r.head<3>() = w_r * err.e.head<3>();
  r.tail<3>() = w_t * err.e.tail<3>();
  if (J == nullptr) return true;
  // dx/dxi = -J_f_x^-1 J_f_xi (forward_kinematics.h), folded into de/dxi = J_e_x dx/dxi
  // with buffers reused across poses.
  Eigen::Matrix4d J_f_x;
  model_->ConstraintJacobians(q, fk.x, &J_f_x, nullptr, &J_f_xi_);
  const Eigen::PartialPivLU<Eigen::Matrix4d> lu(J_f_x);
  if (!(lu.rcond() > 1e-12)) {  // ForwardKinematicsJacobians' singularity threshold
    if (why != nullptr) *why = PoseName(row) + ": forward kinematics singular";
    return false;
  }
  const Eigen::Matrix<double, 6, 4> J_e_f = -err.J_e_x * lu.inverse();
  const int n_kin = p.kinematic_count();
  auto block = J->middleRows(row0, 6);
  block.leftCols(n_kin).noalias() = J_e_f.lazyProduct(J_f_xi_);  // small: no GEMM
  block.middleCols<6>(p.bc_offset()) = err.J_e_bc;
  block.middleCols<6>(p.te_offset()) = err.J_e_te;
  block.topRows<3>() *= w_r;
  block.bottomRows<3>() *= w_t;
  return true;
}

FreeParameterResiduals::FreeParameterResiduals(IdentificationCost* cost, const ParameterVector& p)
    : FreeParameterResiduals(
          [cost](const ParameterVector& q, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
            return cost->Evaluate(q, r, J);
          },
          p) {}

FreeParameterResiduals::FreeParameterResiduals(ParameterCost cost, const ParameterVector& p)
    : cost_(std::move(cost)), free_(p.FreeIndices()), work_(p), values_(p.values()) {}

bool FreeParameterResiduals::operator()(const Eigen::VectorXd& v, Eigen::VectorXd* r,
                                        Eigen::MatrixXd* J_free) {
  for (size_t k = 0; k < free_.size(); ++k) values_[free_[k]] = v[static_cast<Eigen::Index>(k)];
  work_.set_values(values_);
  if (J_free == nullptr) return cost_(work_, r, nullptr);
  if (!cost_(work_, r, &J_all_)) return false;
  J_free->resize(J_all_.rows(), static_cast<Eigen::Index>(free_.size()));
  for (size_t k = 0; k < free_.size(); ++k) {
    J_free->col(static_cast<Eigen::Index>(k)) = J_all_.col(free_[k]);
  }
  return true;
}

}  // namespace h4::host

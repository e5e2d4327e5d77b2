// The identification parameter vector; see parameter_vector.h.
#include "host/identification/parameter_vector.h"

#include <cmath>
#include <stdexcept>

#include "common/geometry/rotation.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host {

const std::vector<std::string>& TransformParameterNames() {
  static const std::vector<std::string> names = {"X_BC.tx", "X_BC.ty", "X_BC.tz", "X_BC.rx",
                                                 "X_BC.ry", "X_BC.rz", "X_TE.tx", "X_TE.ty",
                                                 "X_TE.tz", "X_TE.rx", "X_TE.ry", "X_TE.rz"};
  return names;
}

Vector6d TransformToParameters(const RigidTransform& X) {
  Vector6d v;
  v.head<3>() = X.translation();
  v.tail<3>() = X.rpy();
  return v;
}

RigidTransform TransformFromParameters(const Vector6d& v) {
  return RigidTransform::FromTranslationRpy(v.head<3>(), v.tail<3>());
}

ParameterVector::ParameterVector(const KinematicModel& model, const RigidTransform& X_BC,
                                 const RigidTransform& X_TE)
    : kinematic_count_(static_cast<int>(model.parameter_names().size())),
      names_(model.parameter_names()) {
  for (const std::string& n : TransformParameterNames()) names_.push_back(n);
  values_.resize(static_cast<Eigen::Index>(names_.size()));
  values_.head(kinematic_count_) = model.parameters();
  values_.segment<6>(bc_offset()) = TransformToParameters(X_BC);
  values_.segment<6>(te_offset()) = TransformToParameters(X_TE);
  fixed_reason_.assign(names_.size(), std::string());
}

int ParameterVector::IndexOf(const std::string& name) const {
  for (size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) return static_cast<int>(i);
  }
  return -1;
}

void ParameterVector::set_X_BC(const RigidTransform& X) {
  values_.segment<6>(bc_offset()) = TransformToParameters(X);
}

void ParameterVector::set_X_TE(const RigidTransform& X) {
  values_.segment<6>(te_offset()) = TransformToParameters(X);
}

void ParameterVector::AppendCameraBlock(const std::vector<std::string>& names,
                                        const Eigen::VectorXd& values) {
  if (camera_count() != 0 || static_cast<Eigen::Index>(names.size()) != values.size()) {
    throw std::invalid_argument("AppendCameraBlock: a camera block exists or sizes differ");
  }
  const Eigen::Index old_size = values_.size();
  values_.conservativeResize(old_size + values.size());
  values_.tail(values.size()) = values;
  names_.insert(names_.end(), names.begin(), names.end());
  fixed_reason_.resize(names_.size());
}

void ParameterVector::Fix(int i, const std::string& reason) {
  fixed_reason_[static_cast<size_t>(i)] = reason.empty() ? std::string("fixed") : reason;
}

void ParameterVector::FreeAll() {
  for (std::string& r : fixed_reason_) r.clear();
}

std::vector<int> ParameterVector::FreeIndices() const {
  std::vector<int> free;
  for (int i = 0; i < size(); ++i) {
    if (is_free(i)) free.push_back(i);
  }
  return free;
}

Eigen::VectorXd ParameterVector::FreeValues() const {
  const std::vector<int> free = FreeIndices();
  Eigen::VectorXd v(static_cast<Eigen::Index>(free.size()));
  for (size_t k = 0; k < free.size(); ++k) v[static_cast<Eigen::Index>(k)] = values_[free[k]];
  return v;
}

void ParameterVector::SetFreeValues(const Eigen::VectorXd& v) {
  const std::vector<int> free = FreeIndices();
  for (size_t k = 0; k < free.size(); ++k) values_[free[k]] = v[static_cast<Eigen::Index>(k)];
}

ParameterVector ConvertModel12To31(const ParameterVector& p12, KinematicModel* model31) {
  const Model12Parameters m12 = Model12::FromVector(p12.kinematic_values());
  const Model31Parameters m31 = NominalModel31(m12);
  const Eigen::VectorXd xi = Model31::ToVector(m31);
  if (model31->parameter_names() != Model31::ParameterNames()) {
    throw std::invalid_argument("ConvertModel12To31: the target model is not Model 31");
  }
  model31->set_parameters(xi);
  return ParameterVector(*model31, NominalX_B31B(m12) * p12.X_BC(), p12.X_TE());
}

}  // namespace h4::host

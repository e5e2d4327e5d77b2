// The identification parameter vector (common/README.md#identification): the kinematic
// parameters of a model followed by X_BC and X_TE as (tx ty tz rx ry rz), R = Rz Ry Rx,
// named "X_BC.tx" ... "X_TE.rz", with a free/fixed mask that records why a parameter is
// fixed. Also the Model 12 -> Model 31 conversion of a parameter set (paper III.C).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// "X_BC.tx" .. "X_BC.rz", "X_TE.tx" .. "X_TE.rz" (12 names).
const std::vector<std::string>& TransformParameterNames();

/// (tx, ty, tz, rx, ry, rz) of a transform, m and rad, R = Rz(rz) Ry(ry) Rx(rx).
Vector6d TransformToParameters(const RigidTransform& X);
RigidTransform TransformFromParameters(const Vector6d& v);

class ParameterVector {
 public:
  /// All parameters free. The model's names come first, then the 12 transform names.
  ParameterVector(const KinematicModel& model, const RigidTransform& X_BC,
                  const RigidTransform& X_TE);

  int size() const { return static_cast<int>(names_.size()); }
  /// Number of kinematic parameters (13 for Model 12, 31 for Model 31).
  int kinematic_count() const { return kinematic_count_; }
  /// Index of X_BC.tx and X_TE.tx.
  int bc_offset() const { return kinematic_count_; }
  int te_offset() const { return kinematic_count_ + 6; }

  const std::vector<std::string>& names() const { return names_; }
  const Eigen::VectorXd& values() const { return values_; }
  /// Precondition: v.size() == size().
  void set_values(const Eigen::VectorXd& v) { values_ = v; }
  /// Index of a parameter by common/README.md name, or -1.
  int IndexOf(const std::string& name) const;

  Eigen::VectorXd kinematic_values() const { return values_.head(kinematic_count_); }
  RigidTransform X_BC() const { return TransformFromParameters(values_.segment<6>(bc_offset())); }
  RigidTransform X_TE() const { return TransformFromParameters(values_.segment<6>(te_offset())); }
  void set_X_BC(const RigidTransform& X);
  void set_X_TE(const RigidTransform& X);
  /// Index of the first parameter after X_TE: the camera block of the corner path
  /// (camera_parameters.h), absent (== size()) on the pose path.
  int camera_offset() const { return kinematic_count_ + 12; }
  int camera_count() const { return size() - camera_offset(); }
  /// Appends named free parameters after X_TE (the camera block). Precondition: no camera
  /// block yet, names.size() == values.size().
  void AppendCameraBlock(const std::vector<std::string>& names, const Eigen::VectorXd& values);
  Eigen::VectorXd camera_values() const { return values_.tail(camera_count()); }
  /// Copies the kinematic values into a model of the same kind.
  void ApplyTo(KinematicModel* model) const { model->set_parameters(kinematic_values()); }

  bool is_free(int i) const { return fixed_reason_[static_cast<size_t>(i)].empty(); }
  /// Empty when free.
  const std::string& fixed_reason(int i) const { return fixed_reason_[static_cast<size_t>(i)]; }
  /// Fixes parameter i at its current value; `reason` must be non-empty.
  void Fix(int i, const std::string& reason);
  void Free(int i) { fixed_reason_[static_cast<size_t>(i)].clear(); }
  void FreeAll();
  /// Indices of the free parameters, ascending.
  std::vector<int> FreeIndices() const;
  int free_count() const { return static_cast<int>(FreeIndices().size()); }
  Eigen::VectorXd FreeValues() const;
  /// Precondition: v.size() == free_count().
  void SetFreeValues(const Eigen::VectorXd& v);

 private:
  int kinematic_count_ = 0;
  std::vector<std::string> names_;
  Eigen::VectorXd values_;
  std::vector<std::string> fixed_reason_;
};

/// The nominal Model 31 parameter vector equivalent to a Model 12 one (paper III.C: Model
/// 31 starts from the Model 12 result): kinematics from NominalModel31, X_BC mapped to
/// B31, X_TE unchanged, all free (X_B31C = NominalX_B31B * X_BC). `model31` supplies the Model 31
/// implementation (its parameters are overwritten). Precondition: p12 is a Model 12 vector.
ParameterVector ConvertModel12To31(const ParameterVector& p12, KinematicModel* model31);

}  // namespace h4::host

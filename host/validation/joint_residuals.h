// Joint-space validation (paper IV.D, Table 3): on the held-out poses, the wrapped residual
// q~ - IK(X_BC X_CT X_TE) per joint (measured minus model, the paper's sign), its mean and
// RMS; and the positioning error of forward kinematics from the readings against the
// measured end-effector pose (the paper's "26 mm and 0.022 rad" a priori).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/geometry/rigid_transform.h"
#include "host/formats/dataset_csv.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct JointResidualStats {
  std::array<double, 4> mean{};      ///< per joint, rad
  std::array<double, 4> rms{};       ///< per joint, rad
  int poses = 0;                     ///< rows used
  std::vector<int64_t> unreachable;  ///< pose ids whose measured pose the model cannot reach
  std::vector<int64_t> pose_ids;     ///< rows used, in order
  std::vector<std::array<double, 4>> residuals;  ///< per used row, rad
};

/// Residuals of `rows` (all of them) with `model` and the placements X_BC, X_TE in the
/// model's base frame. Rows out of the model's reach are listed, not used.
JointResidualStats JointResidualsOf(const KinematicModel& model, const RigidTransform& X_BC,
                                    const RigidTransform& X_TE,
                                    const std::vector<DatasetRow>& rows);

struct PositioningError {
  double position_mean = 0.0;  ///< mean |p_FK - p_measured|, m
  double position_rms = 0.0;   ///< m
  double theta_mean = 0.0;     ///< mean |wrap(theta_FK - theta_measured)|, rad
  double theta_rms = 0.0;      ///< rad
  int poses = 0;
  std::vector<int64_t> failed;  ///< pose ids where forward kinematics failed
};

/// Forward kinematics of each row's readings against X_BE = X_BC X_CT X_TE (eq. (6)).
PositioningError PositioningErrorOf(const KinematicModel& model, const RigidTransform& X_BC,
                                    const RigidTransform& X_TE,
                                    const std::vector<DatasetRow>& rows);

}  // namespace h4::host

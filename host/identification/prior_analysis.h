// Prior kinematic analysis (paper III.B, `h4cal analyze`): the end-effector of an H4 turns
// about one fixed axis z_B, so the board does too. From the measured rotations R_CT alone:
// the axis in the camera frame (all R_CT_j R_CT_k^T turn about R_CB z_B), the axis in the
// board frame (all R_CT_j^T R_CT_k turn about R_TE z_E), the spread of the per-pose axis
// estimates (the 4-DoF check; the paper measured 0.12 deg), and initial X_BC / X_TE whose
// z axes agree with the data, to start the identification from a rough a priori.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "common/units.h"
#include "host/formats/dataset_csv.h"

namespace h4::host {

struct PriorAnalysisOptions {
  /// Pairs of poses turned by less than this are too noisy for an axis (rad).
  double min_rotation = RadiansFromDegrees(5.0);
};

struct PriorAnalysis {
  bool ok = false;
  std::string message;                                ///< why not ok, or a one-line account
  Eigen::Vector3d axis_C = Eigen::Vector3d::UnitZ();  ///< z_B in C, unit
  Eigen::Vector3d axis_T = Eigen::Vector3d::UnitZ();  ///< z_E (= z_B) in T, unit
  /// RMS angle between each pose's axis estimate and the mean axis, deg (the 4-DoF check).
  double axis_spread_deg = 0.0;
  double axis_spread_T_deg = 0.0;  ///< the same for the axis in T
  int poses_used = 0;
  /// Relative rotations evaluated (a few per pose: the work is linear in the pose count).
  int64_t rotations_compared = 0;
  /// Per row: rotation angle about the axis relative to the first row, rad (theta_j - theta_0).
  std::vector<double> relative_theta;
  /// The a priori placements turned (minimally) so that R_BC^T z_B = axis_C and
  /// R_TE z_B = axis_T; X_BC's translation moved so the mean board position in B is kept.
  RigidTransform X_BC;
  RigidTransform X_TE;
  /// Angles by which the a priori camera and board z axes were off, deg.
  double camera_axis_correction_deg = 0.0;
  double board_axis_correction_deg = 0.0;
};

/// Needs at least 3 rows with rotations of at least options.min_rotation between some pairs.
/// The axis signs follow the a priori placements (z_B up, away from the nacelle).
PriorAnalysis AnalyzeRotationAxis(const std::vector<DatasetRow>& rows,
                                  const RigidTransform& X_BC_apriori,
                                  const RigidTransform& X_TE_apriori,
                                  const PriorAnalysisOptions& options = PriorAnalysisOptions{});

}  // namespace h4::host

// The seven columns x,y,z,qw,qx,qy,qz that carry a measured board pose X_CT in the
// dataset, fk output and board poses CSVs (common/formats/README.md): translation in m, unit
// quaternion w first (any sign; norm 1 within 1e-3).
#pragma once

#include <string>
#include <vector>

#include "common/formats/csv_table.h"
#include "common/geometry/rigid_transform.h"

namespace h4 {

/// No H4 parameter, placement or board pose is larger than this (m): the bound every file's
/// lengths and positions are read against (robot.yaml, the result, the pose columns).
inline constexpr double kMaxRobotSize_m = 10.0;

/// The column names, in the order written.
const std::vector<std::string>& PoseColumnNames();

/// Tolerance on the quaternion norm (common/formats/README.md).
inline constexpr double kQuaternionNormTolerance = 1e-3;

/// Reads the pose of row `row`; a non-number or a translation beyond kMaxRobotSize_m (10 m)
/// names its column, a quaternion whose norm is not 1 within 1e-3 is an error on field
/// "qw,qx,qy,qz".
RigidTransform ReadPoseColumns(const CsvTable& table, size_t row);

/// "x,y,z,qw,qx,qy,qz" values of X (w >= 0), shortest round-trip text.
std::string FormatPoseColumns(const RigidTransform& X);

}  // namespace h4

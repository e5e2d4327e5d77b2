// Pose columns of the CSV formats; see pose_columns.h.
#include "common/formats/pose_columns.h"

#include <cmath>

#include "common/formats/number_text.h"
#include "common/geometry/rotation.h"

namespace h4 {

const std::vector<std::string>& PoseColumnNames() {
  static const std::vector<std::string> names = {"x", "y", "z", "qw", "qx", "qy", "qz"};
  return names;
}

namespace {

// A board within kMaxRobotSize_m of the camera, the result JSON's bound on translations:
// 1e308 read as a position made `analyze` print -inf and `check` inf.
double Translation(const CsvTable& table, size_t row, const char* column) {
  const double value = table.GetDouble(row, column);
  if (!(std::abs(value) <= kMaxRobotSize_m)) {
    table.Fail(row, column,
               "expected a translation within " + FormatDouble(kMaxRobotSize_m, column) +
                   " m, got " + FormatDouble(value, column));
  }
  return value;
}

}  // namespace

RigidTransform ReadPoseColumns(const CsvTable& table, size_t row) {
  const Eigen::Vector3d p(Translation(table, row, "x"), Translation(table, row, "y"),
                          Translation(table, row, "z"));
  const double w = table.GetDouble(row, "qw");
  const double x = table.GetDouble(row, "qx");
  const double y = table.GetDouble(row, "qy");
  const double z = table.GetDouble(row, "qz");
  Eigen::Matrix3d R;
  if (!RotationFromQuaternion(w, x, y, z, &R, kQuaternionNormTolerance)) {
    const double norm = std::sqrt(w * w + x * x + y * y + z * z);
    table.Fail(row, "qw,qx,qy,qz",
               "expected a unit quaternion (norm 1 within 1e-3), got norm " +
                   (std::isfinite(norm) ? FormatDouble(norm, "norm") : std::string("infinite")));
  }
  return RigidTransform(R, p);
}

std::string FormatPoseColumns(const RigidTransform& X) {
  const Eigen::Vector3d& p = X.translation();
  const Eigen::Vector4d q = X.quaternion_wxyz();
  return FormatDouble(p.x(), "x") + "," + FormatDouble(p.y(), "y") + "," +
         FormatDouble(p.z(), "z") + "," + FormatDouble(q[0], "qw") + "," +
         FormatDouble(q[1], "qx") + "," + FormatDouble(q[2], "qy") + "," + FormatDouble(q[3], "qz");
}

}  // namespace h4

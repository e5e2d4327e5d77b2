// The paired dataset CSV (common/formats/README.md): one row per robot pose, encoder readings
// q1..q4 and the camera's measurement X_CT of the board.
//   pose_id,utime,q1,q2,q3,q4,x,y,z,qw,qx,qy,qz[,set][,sigma_t,sigma_r]
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry/rigid_transform.h"

namespace h4 {

enum class PoseSet { kCalib, kValid };

struct DatasetRow {
  int64_t pose_id = 0;
  int64_t utime = 0;              ///< microseconds since the Unix epoch
  std::array<double, 4> q{};      ///< encoder readings, rad
  RigidTransform X_CT;            ///< measured board pose in the camera frame
  std::optional<PoseSet> set;     ///< the `set` column when present
  std::optional<double> sigma_t;  ///< per-pose translation std, m
  std::optional<double> sigma_r;  ///< per-pose rotation std, rad
};

/// The standard deviations a dataset row may carry: from a nanometre (nanoradian), far
/// below any camera's, up to a metre (half a turn). Writers of datasets (the campaign)
/// must not record a sigma outside them.
struct SigmaBounds {
  double min;
  double max;
};
inline constexpr SigmaBounds kSigmaTBounds{1e-9, 1.0};               // m
inline constexpr SigmaBounds kSigmaRBounds{1e-9, std::numbers::pi};  // rad

/// The largest encoder reading a dataset row may carry, rad: one turn either way. A larger
/// value is a unit mistake (degrees, encoder counts) or damage, and 1e308 made the kinematics
/// non-finite. The reader refuses a row beyond it, and the campaign refuses such a joint
/// reading where it enters (measurement_pairing.h CheckJointState): one bound for both.
inline constexpr double kMaxJointReading = 2.0 * std::numbers::pi;
/// Whether `q` is a joint reading a dataset may hold: finite, |q| <= kMaxJointReading.
inline bool IsJointReadingInBounds(double q) { return std::abs(q) <= kMaxJointReading; }

/// Reads a dataset CSV; throws FormatError naming file, line and field on any
/// malformed input (missing column or field, non-number, non-unit quaternion,
/// duplicate pose_id, unknown set). `source_name` is used in messages. The optional
/// `set` column must hold calib or valid on every row; `sigma_t`/`sigma_r` cells may be
/// empty (absent) but must lie within kSigmaTBounds / kSigmaRBounds when given.
std::vector<DatasetRow> ReadDatasetCsv(const std::string& path);
std::vector<DatasetRow> ParseDatasetCsv(const std::string& text, const std::string& source_name);

/// Writes the header and rows (shortest round-trip doubles: read(write(x)) gives the same
/// numbers; the rotation of X_CT goes through a quaternion, a few ulp); `set`/`sigma`
/// columns are written when any row has them. Throws std::invalid_argument on a
/// non-finite number or when some rows have a set and others not.
void WriteDatasetCsv(const std::string& path, const std::vector<DatasetRow>& rows);
std::string FormatDatasetCsv(const std::vector<DatasetRow>& rows);

/// Header line of a dataset file (no trailing newline), and one formatted row, for
/// writers that append durably row by row (the campaign).
std::string DatasetCsvHeader(bool with_set, bool with_sigma);
std::string DatasetCsvLine(const DatasetRow& row, bool with_set, bool with_sigma);

}  // namespace h4

// The joints CSV (common/formats/README.md): `pose_id,q1,q2,q3,q4`, encoder readings in rad. Input
// of `h4cal fk`, output of `h4cal ik`.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace h4 {

struct JointsRow {
  int64_t pose_id = 0;
  std::array<double, 4> q{};  ///< encoder readings q1..q4, rad
};

/// Reads a joints CSV; throws FormatError naming file, line and field on a missing
/// column or field, a non-number or a duplicate pose_id.
std::vector<JointsRow> ParseJointsCsv(const std::string& text, const std::string& source_name);
std::vector<JointsRow> ReadJointsCsv(const std::string& path);

/// Header and rows, shortest round-trip numbers.
std::string FormatJointsCsv(const std::vector<JointsRow>& rows);
void WriteJointsCsv(const std::string& path, const std::vector<JointsRow>& rows);

}  // namespace h4

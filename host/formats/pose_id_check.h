// Reads the `pose_id` column of a CSV and rejects a pose id seen on an earlier line:
// every CSV keyed by pose id (dataset, joints, poses, fk output) needs them unique.
#pragma once

#include <cstdint>
#include <map>

#include "common/formats/csv_table.h"

namespace h4 {

class PoseIdCheck {
 public:
  /// The integer pose_id of row `row`; throws FormatError on a non-integer or a
  /// duplicate (the message gives the line of the first one).
  int64_t Read(const CsvTable& table, size_t row);

 private:
  std::map<int64_t, int> line_of_id_;
};

}  // namespace h4

// Duplicate pose id detection; see pose_id_check.h.
#include "host/formats/pose_id_check.h"

#include <string>

#include <fmt/core.h>

namespace h4 {

int64_t PoseIdCheck::Read(const CsvTable& table, size_t row) {
  const int64_t id = table.GetInt64(row, "pose_id");
  const auto [previous, inserted] = line_of_id_.emplace(id, table.line(row));
  if (!inserted) {
    table.Fail(row, "pose_id",
               fmt::format("duplicate pose_id {} (first on line {})", id, previous->second));
  }
  return id;
}

}  // namespace h4

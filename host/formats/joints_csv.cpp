// The joints CSV; see joints_csv.h.
#include "host/formats/joints_csv.h"

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "host/formats/pose_id_check.h"

namespace h4 {

std::vector<JointsRow> ParseJointsCsv(const std::string& text, const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns({"pose_id", "q1", "q2", "q3", "q4"});
  PoseIdCheck ids;
  return ReadCsvRows(table, [&table, &ids](size_t r) {
    JointsRow row;
    row.pose_id = ids.Read(table, r);
    for (size_t i = 0; i < 4; ++i) row.q[i] = table.GetDouble(r, fmt::format("q{}", i + 1));
    return row;
  });
}

std::vector<JointsRow> ReadJointsCsv(const std::string& path) {
  return ParseJointsCsv(ReadTextFile(path), path);
}

std::string FormatJointsCsv(const std::vector<JointsRow>& rows) {
  return FormatCsvLines("pose_id,q1,q2,q3,q4", rows, [](const JointsRow& row) {
    std::string line = fmt::format("{}", row.pose_id);
    for (size_t i = 0; i < 4; ++i) line += "," + FormatDouble(row.q[i], "q");
    return line;
  });
}

void WriteJointsCsv(const std::string& path, const std::vector<JointsRow>& rows) {
  WriteTextFile(path, FormatJointsCsv(rows));
}

}  // namespace h4

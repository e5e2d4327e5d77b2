// Offline board poses CSV; see board_poses_csv.h.
#include "common/formats/board_poses_csv.h"

#include <limits>
#include <stdexcept>

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "common/formats/pose_columns.h"

namespace h4 {
namespace {

std::optional<double> NonNegative(const CsvTable& table, size_t r, const char* column,
                                  bool strictly_positive) {
  const std::optional<double> value = table.GetOptionalDouble(r, column);
  if (value && (*value < 0.0 || (strictly_positive && *value == 0.0))) {
    table.Fail(r, column,
               std::string(strictly_positive ? "expected a positive number"
                                             : "expected a non-negative number") +
                   ", got " + table.Cell(r, column));
  }
  return value;
}

std::string Optional(const std::optional<double>& value, const char* field) {
  return value ? FormatDouble(*value, field) : std::string();
}

}  // namespace

std::vector<BoardPoseRow> ParseBoardPosesCsv(const std::string& text,
                                             const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns({"image"});
  table.RequireColumns(PoseColumnNames());
  table.RequireColumns({"corners", "rms_px", "sigma_t", "sigma_r"});
  std::vector<BoardPoseRow> rows;
  rows.reserve(table.num_rows());
  for (size_t r = 0; r < table.num_rows(); ++r) {
    BoardPoseRow row;
    row.image = table.GetString(r, "image");
    size_t empty = 0;
    for (const std::string& column : PoseColumnNames()) empty += table.IsEmpty(r, column) ? 1 : 0;
    if (empty == 0) {
      row.X_CT = ReadPoseColumns(table, r);
    } else if (empty < PoseColumnNames().size()) {
      for (const std::string& column : PoseColumnNames()) {
        if (table.IsEmpty(r, column)) {
          table.Fail(r, column,
                     "expected a number: the pose fields x..qz are either all empty (no board) "
                     "or all numbers");
        }
      }
    }
    const int64_t corners = table.GetInt64(r, "corners");
    if (corners < 0 || corners > std::numeric_limits<int>::max()) {
      table.Fail(r, "corners",
                 "expected a non-negative corner count, got " + table.Cell(r, "corners"));
    }
    row.corners = static_cast<int>(corners);
    row.rms_px = NonNegative(table, r, "rms_px", false);
    if (row.X_CT && !row.rms_px) {
      table.Fail(r, "rms_px", "expected the reprojection RMS of the pose, got an empty field");
    }
    row.sigma_t = NonNegative(table, r, "sigma_t", true);
    row.sigma_r = NonNegative(table, r, "sigma_r", true);
    rows.push_back(row);
  }
  return rows;
}

std::vector<BoardPoseRow> ReadBoardPosesCsv(const std::string& path) {
  return ParseBoardPosesCsv(ReadTextFile(path), path);
}

std::string FormatBoardPosesCsv(const std::vector<BoardPoseRow>& rows) {
  const char* header = "image,x,y,z,qw,qx,qy,qz,corners,rms_px,sigma_t,sigma_r";
  return FormatCsvLines(header, rows, [](const BoardPoseRow& row) {
    if (row.image.empty()) throw std::invalid_argument("board pose row without an image name");
    return fmt::format("{},{},{},{},{},{}", CsvQuote(row.image),
                       (row.X_CT ? FormatPoseColumns(*row.X_CT) : ",,,,,,"), row.corners,
                       Optional(row.rms_px, "rms_px"), Optional(row.sigma_t, "sigma_t"),
                       Optional(row.sigma_r, "sigma_r"));
  });
}

void WriteBoardPosesCsv(const std::string& path, const std::vector<BoardPoseRow>& rows) {
  WriteTextFile(path, FormatBoardPosesCsv(rows));
}

}  // namespace h4

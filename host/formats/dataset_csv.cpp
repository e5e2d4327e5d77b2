// The paired dataset CSV (common/formats/README.md#paired-dataset-csv); see dataset_csv.h.
#include "host/formats/dataset_csv.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/file_kind.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"
#include "common/formats/pose_columns.h"
#include "host/formats/pose_id_check.h"

namespace h4 {
namespace {

const std::vector<std::string> kRequired = {"pose_id", "utime", "q1", "q2", "q3", "q4", "x",
                                            "y",       "z",     "qw", "qx", "qy", "qz"};

// A sigma the weighted cost can use: 1/sigma^2 of a sigma below ~1e-154 overflows and
// the identification never ends, so sigmas are bounded to what a camera can measure.
std::optional<double> BoundedSigma(const CsvTable& table, size_t row, const char* column,
                                   const SigmaBounds& bounds, const std::string& unit) {
  const std::optional<double> sigma = table.GetOptionalDouble(row, column);
  if (sigma && !(*sigma >= bounds.min && *sigma <= bounds.max)) {
    table.Fail(row, column,
               "expected a standard deviation in [" + FormatDouble(bounds.min, column) + ", " +
                   FormatDouble(bounds.max, column) + "] " + unit + ", got " +
                   FormatDouble(*sigma, column));
  }
  return sigma;
}

// An encoder reading within a turn (kMaxJointReading).
double JointReading(const CsvTable& table, size_t row, const std::string& column) {
  const double value = table.GetDouble(row, column);
  if (!IsJointReadingInBounds(value)) {
    table.Fail(row, column,
               "expected a joint angle within one turn (|q| <= 2 pi rad), got " +
                   FormatDouble(value, column));
  }
  return value;
}

}  // namespace

std::vector<DatasetRow> ParseDatasetCsv(const std::string& text, const std::string& source_name) {
  if (GuessFileKind(text) == FileKind::kYaml) {
    throw FormatError(source_name, 1, "",
                      "this looks like a YAML file (a robot.yaml?), not a dataset CSV (were "
                      "--robot and --data swapped?)");
  }
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns(kRequired);
  std::vector<DatasetRow> rows;
  rows.reserve(table.num_rows());
  PoseIdCheck ids;
  for (size_t r = 0; r < table.num_rows(); ++r) {
    DatasetRow row;
    row.pose_id = ids.Read(table, r);
    row.utime = table.GetInt64(r, "utime");
    for (size_t i = 0; i < 4; ++i) row.q[i] = JointReading(table, r, fmt::format("q{}", i + 1));
    row.X_CT = ReadPoseColumns(table, r);
    if (table.HasColumn("set")) {
      const std::string& set = table.Cell(r, "set");
      if (set == "calib") {
        row.set = PoseSet::kCalib;
      } else if (set == "valid") {
        row.set = PoseSet::kValid;
      } else {
        table.Fail(r, "set", "expected 'calib' or 'valid', got '" + set + "'");
      }
    }
    row.sigma_t = BoundedSigma(table, r, "sigma_t", kSigmaTBounds, "m");
    row.sigma_r = BoundedSigma(table, r, "sigma_r", kSigmaRBounds, "rad");
    rows.push_back(row);
  }
  return rows;
}

std::vector<DatasetRow> ReadDatasetCsv(const std::string& path) {
  return ParseDatasetCsv(ReadTextFile(path), path);
}

std::string DatasetCsvHeader(bool with_set, bool with_sigma) {
  std::string header = "pose_id,utime,q1,q2,q3,q4,x,y,z,qw,qx,qy,qz";
  if (with_set) header += ",set";
  if (with_sigma) header += ",sigma_t,sigma_r";
  return header;
}

std::string DatasetCsvLine(const DatasetRow& row, bool with_set, bool with_sigma) {
  std::string line = fmt::format("{},{}", row.pose_id, row.utime);
  for (size_t i = 0; i < 4; ++i) line += "," + FormatDouble(row.q[i], "q");
  line += "," + FormatPoseColumns(row.X_CT);
  if (with_set) {
    // An empty `set` would not read back: a file either splits every row or none.
    if (!row.set) {
      throw std::invalid_argument(
          fmt::format("dataset row {} has no set while the file has a set column", row.pose_id));
    }
    line += (*row.set == PoseSet::kCalib) ? ",calib" : ",valid";
  }
  if (with_sigma) {
    line += "," + (row.sigma_t ? FormatDouble(*row.sigma_t, "sigma_t") : std::string());
    line += "," + (row.sigma_r ? FormatDouble(*row.sigma_r, "sigma_r") : std::string());
  }
  return line;
}

std::string FormatDatasetCsv(const std::vector<DatasetRow>& rows) {
  bool with_set = false;
  bool with_sigma = false;
  for (const DatasetRow& row : rows) {
    with_set = with_set || row.set.has_value();
    with_sigma = with_sigma || row.sigma_t.has_value() || row.sigma_r.has_value();
  }
  std::string text = DatasetCsvHeader(with_set, with_sigma) + "\n";
  for (const DatasetRow& row : rows) text += DatasetCsvLine(row, with_set, with_sigma) + "\n";
  return text;
}

void WriteDatasetCsv(const std::string& path, const std::vector<DatasetRow>& rows) {
  WriteTextFile(path, FormatDatasetCsv(rows));
}

}  // namespace h4

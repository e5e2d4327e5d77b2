// Poses CSV and fk output; see poses_csv.h.
#include "host/formats/poses_csv.h"

#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "common/formats/pose_columns.h"
#include "host/formats/pose_id_check.h"

namespace h4 {
namespace {

const std::vector<std::string> kPoseColumns = {"pose_id", "X", "Y", "Z", "theta"};

// A cell within [-limit, limit]; `unit` names the unit in the message.
double Bounded(const CsvTable& table, size_t r, const char* column, double limit,
               const std::string& unit) {
  const double value = table.GetDouble(r, column);
  if (std::abs(value) > limit) {
    table.Fail(r, column,
               "expected |" + std::string(column) + "| <= " + FormatDouble(limit, column) + " " +
                   unit + ", got " + FormatDouble(value, column));
  }
  return value;
}

EndEffectorPoseRow ReadEndEffectorPose(const CsvTable& table, size_t r, PoseIdCheck* ids) {
  EndEffectorPoseRow row;
  row.pose_id = ids->Read(table, r);
  row.X = Bounded(table, r, "X", kMaxEndEffectorPosition_m, "m");
  row.Y = Bounded(table, r, "Y", kMaxEndEffectorPosition_m, "m");
  row.Z = Bounded(table, r, "Z", kMaxEndEffectorPosition_m, "m");
  // theta = 20 is degrees given by mistake: the H4 turns less than half a turn each way.
  row.theta = Bounded(table, r, "theta", std::numbers::pi, "rad (pi)");
  return row;
}

std::string FormatEndEffectorPose(const EndEffectorPoseRow& row) {
  return fmt::format("{},{},{},{},{}", row.pose_id, FormatDouble(row.X, "X"),
                     FormatDouble(row.Y, "Y"), FormatDouble(row.Z, "Z"),
                     FormatDouble(row.theta, "theta"));
}

}  // namespace

std::vector<EndEffectorPoseRow> ParsePosesCsv(const std::string& text,
                                              const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns(kPoseColumns);
  PoseIdCheck ids;
  return ReadCsvRows(table,
                     [&table, &ids](size_t r) { return ReadEndEffectorPose(table, r, &ids); });
}

std::vector<EndEffectorPoseRow> ReadPosesCsv(const std::string& path) {
  return ParsePosesCsv(ReadTextFile(path), path);
}

std::string FormatPosesCsv(const std::vector<EndEffectorPoseRow>& rows) {
  return FormatCsvLines("pose_id,X,Y,Z,theta", rows, FormatEndEffectorPose);
}

void WritePosesCsv(const std::string& path, const std::vector<EndEffectorPoseRow>& rows) {
  WriteTextFile(path, FormatPosesCsv(rows));
}

std::vector<FkRow> ParseFkCsv(const std::string& text, const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns(kPoseColumns);
  table.RequireColumns(PoseColumnNames());
  PoseIdCheck ids;
  return ReadCsvRows(table, [&table, &ids](size_t r) {
    FkRow row;
    row.pose = ReadEndEffectorPose(table, r, &ids);
    row.X_CT = ReadPoseColumns(table, r);
    return row;
  });
}

std::vector<FkRow> ReadFkCsv(const std::string& path) {
  return ParseFkCsv(ReadTextFile(path), path);
}

std::string FormatFkCsv(const std::vector<FkRow>& rows) {
  return FormatCsvLines("pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy,qz", rows, [](const FkRow& row) {
    return FormatEndEffectorPose(row.pose) + "," + FormatPoseColumns(row.X_CT);
  });
}

void WriteFkCsv(const std::string& path, const std::vector<FkRow>& rows) {
  WriteTextFile(path, FormatFkCsv(rows));
}

}  // namespace h4

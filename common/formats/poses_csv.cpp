// Poses CSV and fk output; see poses_csv.h.
#include "common/formats/poses_csv.h"

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "common/formats/pose_columns.h"
#include "common/formats/pose_id_check.h"

namespace h4 {
namespace {

const std::vector<std::string> kPoseColumns = {"pose_id", "X", "Y", "Z", "theta"};

EndEffectorPoseRow ReadEndEffectorPose(const CsvTable& table, size_t r, PoseIdCheck* ids) {
  EndEffectorPoseRow row;
  row.pose_id = ids->Read(table, r);
  row.X = table.GetDouble(r, "X");
  row.Y = table.GetDouble(r, "Y");
  row.Z = table.GetDouble(r, "Z");
  row.theta = table.GetDouble(r, "theta");
  return row;
}

std::string FormatEndEffectorPose(const EndEffectorPoseRow& row) {
  return std::to_string(row.pose_id) + "," + FormatDouble(row.X, "X") + "," +
         FormatDouble(row.Y, "Y") + "," + FormatDouble(row.Z, "Z") + "," +
         FormatDouble(row.theta, "theta");
}

}  // namespace

std::vector<EndEffectorPoseRow> ParsePosesCsv(const std::string& text,
                                              const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns(kPoseColumns);
  PoseIdCheck ids;
  std::vector<EndEffectorPoseRow> rows;
  rows.reserve(table.num_rows());
  for (size_t r = 0; r < table.num_rows(); ++r) rows.push_back(ReadEndEffectorPose(table, r, &ids));
  return rows;
}

std::vector<EndEffectorPoseRow> ReadPosesCsv(const std::string& path) {
  return ParsePosesCsv(ReadTextFile(path), path);
}

std::string FormatPosesCsv(const std::vector<EndEffectorPoseRow>& rows) {
  std::string text = "pose_id,X,Y,Z,theta\n";
  for (const EndEffectorPoseRow& row : rows) text += FormatEndEffectorPose(row) + "\n";
  return text;
}

void WritePosesCsv(const std::string& path, const std::vector<EndEffectorPoseRow>& rows) {
  WriteTextFile(path, FormatPosesCsv(rows));
}

std::vector<FkRow> ParseFkCsv(const std::string& text, const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns(kPoseColumns);
  table.RequireColumns(PoseColumnNames());
  PoseIdCheck ids;
  std::vector<FkRow> rows;
  rows.reserve(table.num_rows());
  for (size_t r = 0; r < table.num_rows(); ++r) {
    FkRow row;
    row.pose = ReadEndEffectorPose(table, r, &ids);
    row.X_CT = ReadPoseColumns(table, r);
    rows.push_back(row);
  }
  return rows;
}

std::vector<FkRow> ReadFkCsv(const std::string& path) {
  return ParseFkCsv(ReadTextFile(path), path);
}

std::string FormatFkCsv(const std::vector<FkRow>& rows) {
  std::string text = "pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy,qz\n";
  for (const FkRow& row : rows) {
    text += FormatEndEffectorPose(row.pose) + "," + FormatPoseColumns(row.X_CT) + "\n";
  }
  return text;
}

void WriteFkCsv(const std::string& path, const std::vector<FkRow>& rows) {
  WriteTextFile(path, FormatFkCsv(rows));
}

}  // namespace h4

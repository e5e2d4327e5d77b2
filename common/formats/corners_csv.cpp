// The board-corner CSV (common/formats/README.md#board-corners-csv); see corners_csv.h.
#include "common/formats/corners_csv.h"

#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"

namespace h4 {
namespace {

// A pixel coordinate beyond this is no image's (images are at most 16384 px a side,
// common/formats/README.md#camera-intrinsics-opencv-filestorage-yaml-or-a-kalibr-camchain); the
// bound leaves room for corners projected off-image.
constexpr double kMaxPixel = 1e6;

int ReadTagId(const CsvTable& table, size_t r) {
  const int64_t tag = table.GetInt64(r, "tag_id");
  // -1 marks a chessboard corner (common/formats/README.md#board-corners-csv); tag ids are never
  // negative.
  if (tag < -1 || tag > std::numeric_limits<int>::max()) {
    table.Fail(
        r, "tag_id",
        "expected a tag id (>= 0, or -1 for a chessboard corner), got " + table.Cell(r, "tag_id"));
  }
  return static_cast<int>(tag);
}

int ReadCornerId(const CsvTable& table, size_t r) {
  const int64_t corner = table.GetInt64(r, "corner");
  if (corner < 0 || corner > std::numeric_limits<int>::max()) {
    table.Fail(r, "corner", "expected a non-negative corner id, got " + table.Cell(r, "corner"));
  }
  return static_cast<int>(corner);
}

double ReadPixel(const CsvTable& table, size_t r, const char* column) {
  const double value = table.GetDouble(r, column);
  if (!(std::abs(value) <= kMaxPixel)) {
    table.Fail(r, column,
               "expected a pixel coordinate within +-1e6 px, got " + table.Cell(r, column));
  }
  return value;
}

// Bounded like the dataset's sigmas (common/formats/README.md#paired-dataset-csv): a weight
// 1/sigma^2 must neither overflow nor come from a sigma no camera measures.
std::optional<double> ReadSigma(const CsvTable& table, size_t r) {
  const std::optional<double> sigma = table.GetOptionalDouble(r, "sigma_px");
  if (sigma && !(*sigma >= kCornerSigmaBounds.min && *sigma <= kCornerSigmaBounds.max)) {
    table.Fail(r, "sigma_px",
               "expected a standard deviation in [" +
                   FormatDouble(kCornerSigmaBounds.min, "sigma_px") + ", " +
                   FormatDouble(kCornerSigmaBounds.max, "sigma_px") + "] px, got " +
                   table.Cell(r, "sigma_px"));
  }
  return sigma;
}

}  // namespace

std::vector<CornerObservation> ParseCornersCsv(const std::string& text,
                                               const std::string& source_name) {
  const CsvTable table = CsvTable::Parse(text, source_name);
  table.RequireColumns({"pose_id", "tag_id", "corner", "u", "v"});
  std::vector<CornerObservation> corners;
  corners.reserve(table.num_rows());
  std::set<std::pair<int64_t, int>> seen;
  for (size_t r = 0; r < table.num_rows(); ++r) {
    CornerObservation c;
    c.pose_id = table.GetInt64(r, "pose_id");
    c.tag_id = ReadTagId(table, r);
    c.corner = ReadCornerId(table, r);
    c.u = ReadPixel(table, r, "u");
    c.v = ReadPixel(table, r, "v");
    c.sigma_px = ReadSigma(table, r);
    // One observation per corner and pose: a second would weigh that corner twice.
    if (!seen.emplace(c.pose_id, c.corner).second) {
      table.Fail(r, "corner",
                 fmt::format("corner {} of pose {} appears twice", c.corner, c.pose_id));
    }
    corners.push_back(c);
  }
  return corners;
}

std::vector<CornerObservation> ReadCornersCsv(const std::string& path) {
  std::vector<CornerObservation> corners = ParseCornersCsv(ReadTextFile(path), path);
  // A corners file given to a command is its input: with no row it gives nothing to fit or
  // map, which a command would otherwise report as "no corners given" and exit 0.
  if (corners.empty()) {
    throw FormatError(path, 0, "", "no corner rows: the file holds only its header");
  }
  return corners;
}

std::string CornersCsvHeader(bool with_sigma) {
  return with_sigma ? "pose_id,tag_id,corner,u,v,sigma_px" : "pose_id,tag_id,corner,u,v";
}

std::string CornersCsvLine(const CornerObservation& c, bool with_sigma) {
  std::string line = fmt::format("{},{},{},{},{}", c.pose_id, c.tag_id, c.corner,
                                 FormatDouble(c.u, "u"), FormatDouble(c.v, "v"));
  if (with_sigma) {
    line += ',';
    if (c.sigma_px) line += FormatDouble(*c.sigma_px, "sigma_px");
  }
  return line;
}

void WriteCornersCsv(const std::string& path, const std::vector<CornerObservation>& corners) {
  bool with_sigma = false;
  for (const CornerObservation& c : corners) with_sigma = with_sigma || c.sigma_px.has_value();
  std::string text = CornersCsvHeader(with_sigma) + "\n";
  for (const CornerObservation& c : corners) text += CornersCsvLine(c, with_sigma) + "\n";
  WriteTextFile(path, text);
}

}  // namespace h4

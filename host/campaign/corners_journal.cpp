// Durable, resumable board-corner appends; see corners_journal.h.
#include "host/campaign/corners_journal.h"

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <stdexcept>

#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

namespace h4::host {
namespace {

// Every corner the campaign writes has a sigma (the camera sends one per corner), so the
// column is always there (common/formats/README.md#board-corners-csv).
constexpr bool kCornersWithSigma = true;

// The first field of `line` (its pose id), or "" when the line has no comma.
std::string PoseIdField(const std::string& line) {
  const size_t comma = line.find(',');
  return comma == std::string::npos ? std::string() : line.substr(0, comma);
}

// `text` without a last line cut by a crash inside a pose's single write, nor the rows of
// that pose before it: a pose's corners are in the file whole or not at all. A cut inside
// the pose id itself cannot tell which pose it was: the last whole pose goes too (its
// corners are then missing; the dataset keeps its row).
std::string WithoutCutPose(std::string text, const std::string& path) {
  if (text.empty() || text.back() == '\n') return text;
  size_t keep = text.rfind('\n');
  keep = (keep == std::string::npos) ? 0 : keep + 1;
  const std::string cut = text.substr(keep);
  spdlog::warn("{}: removing an incomplete last line left by an interrupted run: '{}'", path, cut);
  text.resize(keep);
  std::string pose = PoseIdField(cut);
  while (!text.empty()) {
    const size_t start = text.rfind('\n', text.size() - 2);
    const size_t line_start = (start == std::string::npos) ? 0 : start + 1;
    const std::string line = text.substr(line_start, text.size() - 1 - line_start);
    if (line_start == 0 || (pose.empty() && PoseIdField(line).empty())) break;  // the header
    if (pose.empty()) pose = PoseIdField(line);
    if (PoseIdField(line) != pose) break;
    spdlog::warn("{}: removing a row of pose {}, whose corners the interrupted run cut", path,
                 pose);
    text.resize(line_start);
  }
  return text;
}

}  // namespace

// A Load that throws leaves file_ to close the file (and release its lock).
CornersJournal::CornersJournal(std::string path, JournalFileOps ops)
    : file_(std::move(path), std::move(ops), "--corners-out") {
  Load();
}

void CornersJournal::Load() {
  const std::string text = WithoutCutPose(file_.ReadAll(), path());
  const std::string header = CornersCsvHeader(kCornersWithSigma);
  if (!text.empty()) {
    file_.CheckHeader(text, header);
    for (const CornerObservation& c : ParseCornersCsv(text, path())) pose_ids_.insert(c.pose_id);
  }
  file_.Start(text, header);
}

void CornersJournal::Append(const std::vector<CornerObservation>& corners) {
  if (corners.empty()) throw std::invalid_argument(path() + ": no corners to append");
  const int64_t pose_id = corners.front().pose_id;
  if (Contains(pose_id)) {
    throw std::invalid_argument(
        fmt::format("{}: the corners of pose {} are already recorded", path(), pose_id));
  }
  std::string text;
  for (const CornerObservation& c : corners) {
    if (c.pose_id != pose_id) {
      throw std::invalid_argument(
          fmt::format("{}: corners of poses {} and {} in one append", path(), pose_id, c.pose_id));
    }
    text += CornersCsvLine(c, kCornersWithSigma) + "\n";
  }
  // One write per pose: a kill between poses leaves whole poses only.
  file_.Append(text);
  pose_ids_.insert(pose_id);
}

namespace {

// Refuses corners of poses the dataset has no row of (another campaign's).
void RefuseForeignCorners(const DatasetJournal& dataset, const CornersJournal& corners) {
  std::vector<int64_t> foreign;
  for (int64_t pose_id : corners.pose_ids()) {
    if (!dataset.Contains(pose_id)) foreign.push_back(pose_id);
  }
  if (foreign.empty()) return;
  const size_t shown = std::min<size_t>(foreign.size(), 10);
  throw std::runtime_error(fmt::format(
      "{}: holds the corners of {} poses the dataset {} has no row of (pose {}{}): another "
      "campaign's corners, which the new poses would be mixed with; move the file away or "
      "choose another --corners-out",
      corners.path(), foreign.size(), dataset.path(),
      fmt::join(foreign.begin(), foreign.begin() + static_cast<std::ptrdiff_t>(shown), ", "),
      shown < foreign.size() ? ", ..." : ""));
}

}  // namespace

std::vector<int64_t> ReconcileWithDataset(DatasetJournal& dataset, const CornersJournal& corners) {
  RefuseForeignCorners(dataset, corners);
  const std::vector<DatasetRow>& rows = dataset.rows();
  size_t keep = rows.size();
  while (keep > 0 && !corners.Contains(rows[keep - 1].pose_id)) --keep;
  std::vector<int64_t> cut;
  if (keep > 0) {  // the camera sends corners: the rows after the last with corners lost them
    for (size_t i = keep; i < rows.size(); ++i) cut.push_back(rows[i].pose_id);
  }
  if (!cut.empty()) {
    spdlog::warn(
        "{}: the corners of the last {} poses recorded are not in {} (an interrupted run): "
        "removing their rows to measure them again: pose {}",
        dataset.path(), cut.size(), corners.path(), fmt::join(cut, ", "));
    dataset.DropLastRows(cut.size());
  }
  std::vector<int64_t> without;
  for (const DatasetRow& row : dataset.rows()) {
    if (!corners.Contains(row.pose_id)) without.push_back(row.pose_id);
  }
  if (!without.empty()) {
    spdlog::warn("{}: {} poses of {} have no corners there (kept): pose {}", corners.path(),
                 without.size(), dataset.path(), fmt::join(without, ", "));
  }
  return cut;
}

std::string CornersPathBeside(const std::string& dataset_path) {
  const std::filesystem::path dataset(dataset_path);
  return (dataset.parent_path() / (dataset.stem().string() + ".corners.csv")).string();
}

}  // namespace h4::host

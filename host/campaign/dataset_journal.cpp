// Durable, resumable, exclusive dataset appends; see dataset_journal.h.
#include "host/campaign/dataset_journal.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

#include "common/formats/format_error.h"
#include "host/campaign/journal_file.h"

namespace h4::host {
namespace {

constexpr bool kWithSet = false;
constexpr bool kWithSigma = true;

}  // namespace

// A Load that throws leaves file_ to close the file (and release its lock).
DatasetJournal::DatasetJournal(std::string path, JournalFileOps ops)
    : file_(std::move(path), std::move(ops), "--out") {
  Load();
}

void DatasetJournal::Load() {
  std::string text = file_.ReadAll();
  const std::string header = DatasetCsvHeader(kWithSet, kWithSigma);
  if (!text.empty() && text.back() != '\n') {
    // Only a crash inside the single write of a row leaves this; that row was never
    // acknowledged, so the campaign measures the pose again.
    size_t keep = text.rfind('\n');
    keep = (keep == std::string::npos) ? 0 : keep + 1;
    spdlog::warn("{}: removing an incomplete last line left by an interrupted run: '{}'", path(),
                 text.substr(keep));
    text.resize(keep);
  }
  if (!text.empty()) {
    file_.CheckHeader(text, header);
    rows_ = ParseDatasetCsv(text, path());
    for (const DatasetRow& row : rows_) pose_ids_.insert(row.pose_id);
    resumed_count_ = rows_.size();
  }
  file_.Start(text, header);
}

void DatasetJournal::Append(const DatasetRow& row) {
  if (Contains(row.pose_id)) {
    throw std::invalid_argument(
        fmt::format("{}: pose {} is already recorded", path(), row.pose_id));
  }
  // One write per row: a kill between rows leaves whole rows only.
  const std::string line = DatasetCsvLine(row, kWithSet, kWithSigma) + "\n";
  // Read back through the reader first: a row it would refuse (a joint beyond its bound, a
  // sigma out of range) would make the whole dataset unreadable, so it is never written.
  try {
    ParseDatasetCsv(DatasetCsvHeader(kWithSet, kWithSigma) + "\n" + line, path());
  } catch (const FormatError& e) {
    throw std::invalid_argument(fmt::format(
        "{}: pose {} not recorded, its reader would refuse it: {}", path(), row.pose_id, e.what()));
  }
  file_.Append(line);
  rows_.push_back(row);
  pose_ids_.insert(row.pose_id);
}

void DatasetJournal::DropLastRows(size_t count) {
  if (count > rows_.size()) {
    throw std::invalid_argument(
        fmt::format("{}: {} rows to drop of {}", path(), count, rows_.size()));
  }
  if (count == 0) return;
  // After Load the file holds complete lines only, header first: cut the last `count`.
  std::string text = file_.ReadAll();
  for (size_t k = 0; k < count; ++k) {
    const size_t end = text.rfind('\n', text.size() - 2);
    if (end == std::string::npos) throw std::runtime_error(path() + ": fewer lines than rows");
    text.resize(end + 1);
  }
  file_.Start(text, DatasetCsvHeader(kWithSet, kWithSigma));
  rows_.resize(rows_.size() - count);
  pose_ids_.clear();
  for (const DatasetRow& row : rows_) pose_ids_.insert(row.pose_id);
  resumed_count_ = std::min(resumed_count_, rows_.size());
}

}  // namespace h4::host

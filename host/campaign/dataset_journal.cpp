// Durable, resumable, exclusive dataset appends; see dataset_journal.h.
#include "host/campaign/dataset_journal.h"

#include <stdexcept>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

#include "host/campaign/journal_file.h"

namespace h4::host {
namespace {

constexpr bool kWithSet = false;
constexpr bool kWithSigma = true;

}  // namespace

DatasetJournal::DatasetJournal(std::string path, JournalFileOps ops)
    : path_(std::move(path)), ops_(std::move(ops)) {
  fd_ = OpenLocked(path_);
  try {
    Load();
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void DatasetJournal::Load() {
  std::string text = ReadAll(fd_, path_);
  const std::string header = DatasetCsvHeader(kWithSet, kWithSigma);
  if (!text.empty() && text.back() != '\n') {
    // Only a crash inside the single write of a row leaves this; that row was never
    // acknowledged, so the campaign measures the pose again.
    size_t keep = text.rfind('\n');
    keep = (keep == std::string::npos) ? 0 : keep + 1;
    spdlog::warn("{}: removing an incomplete last line left by an interrupted run: '{}'", path_,
                 text.substr(keep));
    text.resize(keep);
  }
  if (!text.empty()) {
    const std::string first_line = text.substr(0, text.find('\n'));
    if (!IsJournalHeader(first_line, header)) {
      throw std::runtime_error(path_ + ": exists with other columns (line 1: '" + first_line +
                               "'; a campaign writes '" + header +
                               "'): choose another --out or move the file away");
    }
    rows_ = ParseDatasetCsv(text, path_);
    for (const DatasetRow& row : rows_) pose_ids_.insert(row.pose_id);
    resumed_count_ = rows_.size();
  }
  committed_size_ = static_cast<off_t>(text.size());
  if (::ftruncate(fd_, committed_size_) != 0 || ::lseek(fd_, 0, SEEK_END) < 0) {
    throw SystemError(path_, "truncate to its last complete row");
  }
  if (text.empty()) {
    const std::string line = header + "\n";
    AppendDurably(ops_, fd_, line, 0, path_);
    committed_size_ = static_cast<off_t>(line.size());
    // A new file's name must survive a crash too: flush its directory entry.
    FlushDirectoryEntry(path_);
  }
}

DatasetJournal::~DatasetJournal() {
  if (fd_ >= 0) ::close(fd_);  // also releases the lock
}

void DatasetJournal::Append(const DatasetRow& row) {
  if (Contains(row.pose_id)) {
    throw std::invalid_argument(path_ + ": pose " + std::to_string(row.pose_id) +
                                " is already recorded");
  }
  // One write per row: a kill between rows leaves whole rows only.
  const std::string line = DatasetCsvLine(row, kWithSet, kWithSigma) + "\n";
  AppendDurably(ops_, fd_, line, committed_size_, path_);
  committed_size_ += static_cast<off_t>(line.size());
  rows_.push_back(row);
  pose_ids_.insert(row.pose_id);
}

}  // namespace h4::host

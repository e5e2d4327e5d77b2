// Durable, resumable dataset appends; see dataset_journal.h.
#include "host/campaign/dataset_journal.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

namespace h4::host {
namespace {

constexpr bool kWithSet = false;
constexpr bool kWithSigma = true;

std::runtime_error SystemError(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": cannot " + what + ": " + std::strerror(errno));
}

void WriteAll(int fd, const std::string& text, const std::string& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw SystemError(path, "write");
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) throw SystemError(path, "flush to disk (fsync)");
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SystemError(path, "read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

DatasetJournal::DatasetJournal(std::string path) : path_(std::move(path)) {
  std::string text;
  if (::access(path_.c_str(), F_OK) == 0) text = ReadAll(path_);

  const std::string header = DatasetCsvHeader(kWithSet, kWithSigma);
  size_t keep = text.size();
  if (!text.empty() && text.back() != '\n') {
    // Only a crash inside the single write of a row leaves this; that row was never
    // acknowledged, so the campaign measures the pose again.
    keep = text.rfind('\n');
    keep = (keep == std::string::npos) ? 0 : keep + 1;
    spdlog::warn("{}: removing an incomplete last line left by an interrupted run: '{}'", path_,
                 text.substr(keep));
    text.resize(keep);
  }
  if (!text.empty()) {
    const std::string first_line = text.substr(0, text.find('\n'));
    if (first_line != header) {
      throw std::runtime_error(path_ + ": exists with other columns (line 1: '" + first_line +
                               "'; a campaign writes '" + header +
                               "'): choose another --out or move the file away");
    }
    rows_ = ParseDatasetCsv(text, path_);
    for (const DatasetRow& row : rows_) pose_ids_.insert(row.pose_id);
    resumed_count_ = rows_.size();
  }

  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw SystemError(path_, "open for writing");
  if (::ftruncate(fd_, static_cast<off_t>(keep)) != 0 ||
      ::lseek(fd_, 0, SEEK_END) < 0) {
    const std::runtime_error error = SystemError(path_, "truncate to its last complete row");
    ::close(fd_);
    throw error;
  }
  if (text.empty()) {
    WriteAll(fd_, header + "\n", path_);
    // A new file's name must survive a crash too: flush its directory entry.
    const std::string dir = path_.find('/') == std::string::npos
                                ? std::string(".")
                                : path_.substr(0, path_.rfind('/') + 1);
    const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir_fd >= 0) {
      ::fsync(dir_fd);
      ::close(dir_fd);
    }
  }
}

DatasetJournal::~DatasetJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void DatasetJournal::Append(const DatasetRow& row) {
  if (Contains(row.pose_id)) {
    throw std::invalid_argument(path_ + ": pose " + std::to_string(row.pose_id) +
                                " is already recorded");
  }
  // One write per row: a kill between rows leaves whole rows only.
  WriteAll(fd_, DatasetCsvLine(row, kWithSet, kWithSigma) + "\n", path_);
  rows_.push_back(row);
  pose_ids_.insert(row.pose_id);
}

}  // namespace h4::host

// Durable, resumable, exclusive dataset appends; see dataset_journal.h.
#include "host/campaign/dataset_journal.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

namespace h4::host {
namespace {

constexpr bool kWithSet = false;
constexpr bool kWithSigma = true;

std::runtime_error SystemError(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": cannot " + what + ": " + std::strerror(errno));
}

/// The process holding a flock(2) on the file of `fd`, from /proc/locks, or 0 when unknown.
long FlockHolder(int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) return 0;
  const std::string inode = fmt::format("{:02x}:{:02x}:{}", major(st.st_dev), minor(st.st_dev),
                                        static_cast<unsigned long long>(st.st_ino));
  std::ifstream locks("/proc/locks");
  std::string line;
  while (std::getline(locks, line)) {
    // e.g. "3: FLOCK  ADVISORY  WRITE 4242 08:01:1234 0 EOF" (blocked waiters add "->").
    std::istringstream words(line);
    std::string number, kind, mode, access, device;
    long pid = 0;
    if (!(words >> number >> kind >> mode >> access >> pid >> device)) continue;
    if (kind == "FLOCK" && device == inode) return pid;
  }
  return 0;
}

/// Opens `path` for reading and writing (creating it) and takes an exclusive lock for the
/// life of the descriptor: two campaigns on one file would interleave their rows.
int OpenLocked(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw SystemError(path, "open for writing");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw std::runtime_error(path + ": is not a regular file: a dataset must be one");
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const long holder = (error == EWOULDBLOCK) ? FlockHolder(fd) : 0;
    ::close(fd);
    if (error != EWOULDBLOCK) {
      errno = error;
      throw SystemError(path, "lock");
    }
    throw std::runtime_error(path + ": another campaign is writing it" +
                             (holder > 0 ? fmt::format(" (process {})", holder) : std::string()) +
                             ": stop it first, or choose another --out");
  }
  return fd;
}

std::string ReadAll(int fd, const std::string& path) {
  std::string text;
  char buffer[65536];
  for (off_t offset = 0;;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, offset);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw SystemError(path, "read");
    }
    if (n == 0) return text;
    text.append(buffer, static_cast<size_t>(n));
    offset += n;
  }
}

/// Writes all of `text` at the end of `fd` and flushes it to the disk; on any failure the
/// file is cut back to `committed_size` (no part of the row stays behind) and the error
/// thrown names the file and the system's reason.
void AppendDurably(const JournalFileOps& ops, int fd, const std::string& text, off_t committed_size,
                   const std::string& path) {
  const char* failed = nullptr;
  size_t done = 0;
  while (done < text.size() && failed == nullptr) {
    const ssize_t n = ops.write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno != EINTR) failed = "write";
    if (n > 0) done += static_cast<size_t>(n);
  }
  // After a failed fsync the kernel may have dropped the row's pages (and cleared the
  // error): the row is not known to be on the disk, so it is cut off like a failed write.
  if (failed == nullptr && ops.fsync(fd) != 0) failed = "flush to disk (fsync)";
  if (failed == nullptr) return;
  const int error = errno;
  const bool restored =
      ::ftruncate(fd, committed_size) == 0 && ::lseek(fd, committed_size, SEEK_SET) >= 0;
  errno = error;
  std::runtime_error cause = SystemError(path, failed);
  throw std::runtime_error(
      std::string(cause.what()) +
      (restored ? "; the file keeps its complete rows only: free the space (or fix the disk) "
                  "and run the same command to resume"
                : "; the last row may be incomplete: the next run drops it"));
}

void FlushDirectoryEntry(const std::string& path) {
  const std::string dir =
      path.find('/') == std::string::npos ? std::string(".") : path.substr(0, path.rfind('/') + 1);
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

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
    // The readers take a UTF-8 byte order mark and CRLF line ends (common/formats/README.md,
    // "Paired dataset"), which an editor or a spreadsheet may add: the header is compared
    // without them, else the file is refused quoting two headers that print the same.
    std::string_view columns = first_line;
    if (columns.starts_with("\xEF\xBB\xBF")) columns.remove_prefix(3);
    if (columns.ends_with('\r')) columns.remove_suffix(1);
    if (columns != header) {
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

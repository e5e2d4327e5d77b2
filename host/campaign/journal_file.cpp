// The campaign's durable files; see journal_file.h.
#include "host/campaign/journal_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

namespace h4::host {
namespace {

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

std::runtime_error SystemError(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": cannot " + what + ": " + std::strerror(errno));
}

/// Opens `path` for reading and writing (creating it) and takes an exclusive lock for the
/// life of the descriptor: two campaigns on one file would interleave their rows.
int OpenLocked(const std::string& path, const std::string& option) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw SystemError(path, "open for writing");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw std::runtime_error(path + ": is not a regular file: a campaign file must be one");
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
                             ": stop it first, or choose another " + option);
  }
  return fd;
}

std::string ReadWholeFile(int fd, const std::string& path) {
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

bool IsJournalHeader(std::string_view first_line, std::string_view header) {
  if (first_line.starts_with("\xEF\xBB\xBF")) first_line.remove_prefix(3);
  if (first_line.ends_with('\r')) first_line.remove_suffix(1);
  return first_line == header;
}

}  // namespace

JournalFile::JournalFile(std::string path, JournalFileOps ops, std::string option)
    : path_(std::move(path)), ops_(std::move(ops)), option_(std::move(option)) {
  fd_ = OpenLocked(path_, option_);
}

JournalFile::~JournalFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string JournalFile::ReadAll() const { return ReadWholeFile(fd_, path_); }

void JournalFile::CheckHeader(const std::string& text, const std::string& header) const {
  const std::string first_line = text.substr(0, text.find('\n'));
  if (!IsJournalHeader(first_line, header)) {
    throw std::runtime_error(path_ + ": exists with other columns (line 1: '" + first_line +
                             "'; a campaign writes '" + header + "'): choose another " + option_ +
                             " or move the file away");
  }
}

void JournalFile::Start(const std::string& text, const std::string& header) {
  committed_size_ = static_cast<off_t>(text.size());
  if (::ftruncate(fd_, committed_size_) != 0 || ::lseek(fd_, 0, SEEK_END) < 0) {
    throw SystemError(path_, "truncate to its last complete row");
  }
  if (text.empty()) {
    Append(header + "\n");
    // A new file's name must survive a crash too: flush its directory entry.
    FlushDirectoryEntry(path_);
  }
}

void JournalFile::Append(const std::string& text) {
  AppendDurably(ops_, fd_, text, committed_size_, path_);
  committed_size_ += static_cast<off_t>(text.size());
}

}  // namespace h4::host

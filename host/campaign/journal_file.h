// The file operations the campaign's durable files share (the dataset, dataset_journal.h,
// and its corners, corners_journal.h): an exclusive lock, whole-file reads, and appends that
// are either on the disk whole or cut back (common/formats/README.md#writing-files says why
// results are replaced atomically; a journal appends instead, one fsync per pose).
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include <sys/types.h>
#include <unistd.h>

namespace h4::host {

/// The two system calls that make a row durable, replaceable so that tests can inject the
/// faults a disk gives rarely (an fsync that fails with EIO after the write succeeded).
/// Both default to the system's; each returns what the system call would, errno set.
struct JournalFileOps {
  std::function<ssize_t(int fd, const void* data, size_t size)> write = ::write;
  std::function<int(int fd)> fsync = ::fsync;
};

/// One journal file, open and locked for the life of the object: what the dataset and
/// the corners journals share. An exclusive flock(2) is held from construction to
/// destruction: two campaigns on one file would interleave their rows.
class JournalFile {
 public:
  /// Opens `path` for reading and writing (creating it) and locks it. Throws
  /// std::runtime_error naming the file (and the process holding it, when /proc/locks
  /// tells); `option` is the command-line option that chose the file, for the advice.
  JournalFile(std::string path, JournalFileOps ops, std::string option);
  ~JournalFile();  // closes the file, which releases the lock
  JournalFile(const JournalFile&) = delete;
  JournalFile& operator=(const JournalFile&) = delete;

  const std::string& path() const { return path_; }

  /// The whole file; throws naming it when it cannot be read.
  std::string ReadAll() const;
  /// Refuses a file whose first line (of `text`, what was read) is not `header`, naming the
  /// file, both headers and the option. A UTF-8 byte order mark and a CR line end, which an
  /// editor or a spreadsheet may add, do not count.
  void CheckHeader(const std::string& text, const std::string& header) const;
  /// Starts appending after `text`, the complete rows read: cuts the file back to them and,
  /// for a new file, writes `header` durably with its directory entry.
  void Start(const std::string& text, const std::string& header);
  /// Writes all of `text` at the end and flushes it to the disk; on any failure the file is
  /// cut back to its last complete row and the error thrown names the file and the
  /// system's reason.
  void Append(const std::string& text);

 private:
  std::string path_;
  JournalFileOps ops_;
  std::string option_;
  int fd_ = -1;
  off_t committed_size_ = 0;  ///< [bytes] the file up to its last complete, flushed row
};

}  // namespace h4::host

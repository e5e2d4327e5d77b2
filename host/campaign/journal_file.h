// The file operations the campaign's durable files share (the dataset, dataset_journal.h,
// and its corners, corners_journal.h): an exclusive lock, whole-file reads, and appends that
// are either on the disk whole or cut back (common/formats/README.md#writing-files says why
// results are replaced atomically; a journal appends instead, one fsync per pose).
#pragma once

#include <functional>
#include <stdexcept>
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

/// "<path>: cannot <what>: <strerror(errno)>".
std::runtime_error SystemError(const std::string& path, const std::string& what);

/// Opens `path` for reading and writing (creating it) and takes an exclusive lock for the
/// life of the descriptor: two campaigns on one file would interleave their rows. Throws
/// naming the file (and the process holding it, when /proc/locks tells); `option` is the
/// command-line option that chose the file, for the advice.
int OpenLocked(const std::string& path, const std::string& option = "--out");

/// The whole file of `fd`; throws naming `path` when it cannot be read.
std::string ReadAll(int fd, const std::string& path);

/// Writes all of `text` at the end of `fd` and flushes it to the disk; on any failure the
/// file is cut back to `committed_size` (no part of the row stays behind) and the error
/// thrown names the file and the system's reason.
void AppendDurably(const JournalFileOps& ops, int fd, const std::string& text, off_t committed_size,
                   const std::string& path);

/// Whether the first line of a journal file is `header`, read as the CSV readers read it: a
/// UTF-8 byte order mark and a CR line end, which an editor or a spreadsheet may add, do not
/// count (else a resume is refused quoting two headers that print the same).
bool IsJournalHeader(std::string_view first_line, std::string_view header);

/// fsync of the directory holding `path`: a new file's name survives a crash too.
void FlushDirectoryEntry(const std::string& path);

}  // namespace h4::host

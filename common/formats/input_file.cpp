// Opening and reading input files; see input_file.h.
#include "common/formats/input_file.h"

#include <cerrno>
#include <algorithm>
#include <cstring>

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/formats/format_error.h"

namespace h4 {
namespace {

const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

}  // namespace

InputFile::InputFile(const std::string& path) {
  // O_NONBLOCK: opening a FIFO (or a device) for reading would otherwise wait for a writer
  // before the checks below could refuse it; on a regular file it changes nothing.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd_ < 0) {
    error_ = std::string("cannot open: ") + std::strerror(errno);
    return;
  }
  struct stat info {};
  if (::fstat(fd_, &info) != 0) {
    error_ = std::string("cannot stat: ") + std::strerror(errno);
    return;
  }
  if (!S_ISREG(info.st_mode)) {
    error_ = fmt::format("not a regular file ({})", KindOf(info.st_mode));
    return;
  }
  size_ = static_cast<int64_t>(info.st_size);
  mode_ = static_cast<unsigned>(info.st_mode & 07777);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool InputFile::Read(size_t count, std::string* bytes) {
  bytes->assign(count, '\0');
  size_t done = 0;
  while (done < count) {
    const ssize_t n = ::read(fd_, bytes->data() + done, count - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error_ = std::string("read failed: ") + std::strerror(errno);
      return false;
    }
    if (n == 0) break;
    done += static_cast<size_t>(n);
  }
  bytes->resize(done);
  return true;
}

bool InputFile::ReadAll(size_t max_bytes, std::string* bytes) {
  if (!ok()) return false;
  if (static_cast<uint64_t>(size_) > max_bytes) {
    error_ = fmt::format("{} bytes; a file read here holds at most {}", size_, max_bytes);
    return false;
  }
  const auto expected = static_cast<size_t>(size_);
  if (!Read(expected, bytes)) return false;
  if (bytes->size() != expected) {
    error_ = fmt::format("shorter than its size ({} of {} bytes read): it changed while read",
                         bytes->size(), expected);
    return false;
  }
  return true;
}

bool InputFile::ReadPrefix(size_t max_bytes, std::string* bytes) {
  if (!ok()) return false;
  return Read(std::min(max_bytes, static_cast<size_t>(size_)), bytes);
}

std::string ReadDataFile(const std::string& path, size_t max_bytes) {
  InputFile file(path);
  std::string bytes;
  if (!file.ReadAll(max_bytes, &bytes)) throw FormatError(path, 0, "", file.error());
  return bytes;
}

}  // namespace h4

// Reads and checks a key file; see auth_key.h.
#include "messages/bus/auth_key.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

namespace h4::bus {
namespace {

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw std::runtime_error(path + ": auth key: " + why);
}

std::string OctalMode(mode_t mode) {
  return fmt::format("{:04o}", static_cast<unsigned>(mode & 07777));
}

// The checks run on the opened file (fstat), so the file read is the file checked.
void CheckKeyFile(const std::string& path, const struct stat& info) {
  if (!S_ISREG(info.st_mode)) Fail(path, "not a regular file");
  if ((info.st_mode & 077) != 0) {
    Fail(path, "mode " + OctalMode(info.st_mode) +
                   " gives group or others access to the key; run chmod 600 " + path);
  }
  const auto size = static_cast<size_t>(info.st_size);
  if (size < kMinAuthKeyBytes || size > kMaxAuthKeyBytes) {
    Fail(path,
         fmt::format("{} bytes; expected {}..{} (make one with: head -c 32 /dev/urandom > {})",
                     size, kMinAuthKeyBytes, kMaxAuthKeyBytes, path));
  }
}

std::vector<uint8_t> ReadAll(int fd, const std::string& path, size_t size) {
  std::vector<uint8_t> bytes(size);
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, bytes.data() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail(path, n < 0 ? std::strerror(errno) : "shorter than its size");
    done += static_cast<size_t>(n);
  }
  return bytes;
}

}  // namespace

AuthKey ReadAuthKeyFile(const std::string& path) {
  // O_NONBLOCK: opening a FIFO (or a device) for reading would otherwise wait for a writer
  // before the checks below could refuse it; on a regular file it changes nothing.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) Fail(path, std::string("cannot open: ") + std::strerror(errno));
  AuthKey key;
  try {
    struct stat info {};
    if (::fstat(fd, &info) != 0) Fail(path, std::string("cannot stat: ") + std::strerror(errno));
    CheckKeyFile(path, info);
    key.bytes = ReadAll(fd, path, static_cast<size_t>(info.st_size));
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  key.source = path;
  return key;
}

}  // namespace h4::bus

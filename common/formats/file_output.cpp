// Atomic file replacement and same-file checks; see file_output.h.
#include "common/formats/file_output.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <fmt/core.h>
#include <sys/stat.h>
#include <unistd.h>

namespace h4 {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Fail(const std::string& path, const std::string& what, int error) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(error));
}

// A name no other writer uses: this process's id and a per-process counter.
std::string TemporaryPathFor(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  const std::string name =
      fmt::format(".{}.tmp-{}-{}", target.filename().string(), ::getpid(), counter++);
  return (target.parent_path() / name).string();
}

void WriteAll(int fd, const std::string& bytes, const std::string& path) {
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) Fail(path, "write failed", errno);
    written += static_cast<size_t>(n);
  }
}

// The rename is durable only once the directory entry is on disk too.
void SyncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the file itself is already synced and renamed
  ::fsync(fd);
  ::close(fd);
}

// Writes, syncs and closes `temporary`; throws naming `path` (the user's file).
void WriteTemporary(const std::string& temporary, const std::string& bytes,
                    const std::string& path) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) Fail(path, "cannot create a temporary file beside it", errno);
  try {
    WriteAll(fd, bytes, path);
    if (::fsync(fd) != 0) Fail(path, "fsync failed", errno);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) Fail(path, "close failed", errno);
}

// A device or a pipe (`--out /dev/stdout`) cannot be replaced by renaming, and must not
// be: it is written in place.
void WriteInPlace(const std::string& path, const std::string& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) Fail(path, "cannot open for writing", errno);
  try {
    WriteAll(fd, bytes, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) Fail(path, "close failed", errno);
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& bytes) {
  struct stat existing {};
  if (::stat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
    if (S_ISDIR(existing.st_mode)) throw std::runtime_error(path + ": is a directory");
    return WriteInPlace(path, bytes);
  }
  // Through a symbolic link, the file it points to is replaced (the link stays a link).
  std::error_code error;
  const fs::path resolved = fs::is_symlink(path, error) ? fs::canonical(path, error) : fs::path();
  const fs::path target = !error && !resolved.empty() ? resolved : fs::path(path);
  if (target.filename().empty()) throw std::runtime_error(path + ": not a file name");
  const std::string temporary = TemporaryPathFor(target);
  try {
    WriteTemporary(temporary, bytes, path);
    if (::rename(temporary.c_str(), target.c_str()) != 0) Fail(path, "rename failed", errno);
  } catch (...) {
    ::unlink(temporary.c_str());
    throw;
  }
  SyncDirectory(target.parent_path());
}

bool IsSameFile(const std::string& a, const std::string& b) {
  struct stat sa {};
  struct stat sb {};
  const bool a_exists = ::stat(a.c_str(), &sa) == 0;
  const bool b_exists = ::stat(b.c_str(), &sb) == 0;
  if (a_exists && b_exists) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (a_exists != b_exists) return false;
  std::error_code error_a, error_b;
  const fs::path canonical_a = fs::weakly_canonical(a, error_a);
  const fs::path canonical_b = fs::weakly_canonical(b, error_b);
  return !error_a && !error_b && canonical_a == canonical_b;
}

void RequireOutputIsNotAnInput(const NamedPath& output, const std::vector<NamedPath>& inputs) {
  if (output.path.empty()) return;
  for (const NamedPath& input : inputs) {
    if (input.path.empty() || !IsSameFile(output.path, input.path)) continue;
    throw std::invalid_argument(output.option + " " + output.path + " is the same file as " +
                                input.option + " " + input.path +
                                ": refusing to overwrite an input");
  }
}

void RequireOutputFolder(const NamedPath& output) {
  if (output.path.empty()) return;
  const fs::path parent = fs::path(output.path).parent_path();
  std::error_code error;
  if (parent.empty() || fs::is_directory(parent, error)) return;
  throw std::invalid_argument(output.option + " " + output.path + ": the folder " +
                              parent.string() + " does not exist (create it first)");
}

}  // namespace h4

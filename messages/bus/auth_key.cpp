// Reads and checks a key file; see auth_key.h.
#include "messages/bus/auth_key.h"

#include <stdexcept>

#include <fmt/format.h>

#include "common/formats/input_file.h"

namespace h4::bus {
namespace {

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw std::runtime_error(path + ": auth key: " + why);
}

std::string OctalMode(unsigned mode) { return fmt::format("{:04o}", mode & 07777u); }

}  // namespace

// The file is opened and checked by InputFile (common/formats/input_file.h: without waiting
// on a FIFO, fstat on the opened descriptor, so the file read is the file checked).
AuthKey ReadAuthKeyFile(const std::string& path) {
  InputFile file(path);
  if (!file.ok()) Fail(path, file.error());
  if ((file.mode() & 077) != 0) {
    Fail(path, "mode " + OctalMode(file.mode()) +
                   " gives group or others access to the key; run chmod 600 " + path);
  }
  const auto size = static_cast<size_t>(file.size());
  if (size < kMinAuthKeyBytes || size > kMaxAuthKeyBytes) {
    Fail(path,
         fmt::format("{} bytes; expected {}..{} (make one with: head -c 32 /dev/urandom > {})",
                     size, kMinAuthKeyBytes, kMaxAuthKeyBytes, path));
  }
  std::string bytes;
  if (!file.ReadAll(kMaxAuthKeyBytes, &bytes)) Fail(path, file.error());
  AuthKey key;
  key.bytes.assign(bytes.begin(), bytes.end());
  key.source = path;
  return key;
}

}  // namespace h4::bus

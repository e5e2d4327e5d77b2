// systemd notification datagrams over AF_UNIX, as sd_notify(3) sends them, without
// linking libsystemd (one socket call per message; nothing kept open between calls).
#include "firmware/service/sd_notify.h"

#include <cerrno>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace h4::cam {
namespace {

NotifyResult Failed(std::string_view socket_name, const std::string& why) {
  return {NotifyResult::Status::kFailed,
          "sd_notify: socket '" + std::string(socket_name) + "': " + why};
}

// Closes the descriptor on every path out of SdNotifyTo.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// Parses a decimal without sign or trailing characters; nullopt otherwise.
template <typename T>
std::optional<T> ParseDecimal(const char* text) {
  if (text == nullptr || *text == '\0') return std::nullopt;
  const char* end = text + std::strlen(text);
  T value{};
  const auto [ptr, ec] = std::from_chars(text, end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

}  // namespace

NotifyResult SdNotifyTo(std::string_view socket_name, std::string_view state) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  // Abstract names ("@name") have no file: a leading NUL marks them, and the address
  // length (not a terminating NUL) says where the name ends.
  const bool abstract = !socket_name.empty() && socket_name.front() == '@';
  if (!abstract && (socket_name.empty() || socket_name.front() != '/')) {
    return Failed(socket_name, "expected an absolute path or an '@' abstract name");
  }
  if (socket_name.size() >= sizeof(address.sun_path)) {
    return Failed(socket_name,
                  fmt::format("name longer than {} bytes", sizeof(address.sun_path) - 1));
  }
  std::memcpy(address.sun_path, socket_name.data(), socket_name.size());
  if (abstract) address.sun_path[0] = '\0';
  const auto address_size =
      static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + socket_name.size());

  const FileDescriptor fd(::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0));
  if (fd.get() < 0) return Failed(socket_name, std::string("socket(): ") + std::strerror(errno));
  // MSG_NOSIGNAL: a vanished manager must not kill the service with SIGPIPE.
  const ssize_t sent = ::sendto(fd.get(), state.data(), state.size(), MSG_NOSIGNAL,
                                reinterpret_cast<const sockaddr*>(&address), address_size);
  if (sent < 0) return Failed(socket_name, std::string("sendto(): ") + std::strerror(errno));
  if (static_cast<std::size_t>(sent) != state.size()) {
    return Failed(socket_name, fmt::format("sent {} of {} bytes", sent, state.size()));
  }
  return {NotifyResult::Status::kSent, {}};
}

NotifyResult SdNotify(std::string_view state) {
  const char* socket_name = std::getenv("NOTIFY_SOCKET");
  if (socket_name == nullptr || *socket_name == '\0') return {};
  return SdNotifyTo(socket_name, state);
}

NotifyResult NotifyReady() { return SdNotify("READY=1"); }

NotifyResult NotifyWatchdog() { return SdNotify("WATCHDOG=1"); }

NotifyResult NotifyStopping() { return SdNotify("STOPPING=1"); }

NotifyResult NotifyStatus(std::string_view text) {
  // One assignment per line: a newline inside the text would start a bogus assignment.
  std::string message = "STATUS=";
  for (const char c : text) message += (c == '\n' || c == '\r') ? ' ' : c;
  return SdNotify(message);
}

std::optional<std::chrono::microseconds> WatchdogInterval(const char* watchdog_usec,
                                                          const char* watchdog_pid,
                                                          pid_t self_pid) {
  if (watchdog_pid != nullptr) {
    const auto pid = ParseDecimal<long long>(watchdog_pid);
    if (!pid || *pid != static_cast<long long>(self_pid)) return std::nullopt;
  }
  const auto usec = ParseDecimal<unsigned long long>(watchdog_usec);
  if (!usec || *usec == 0 ||
      *usec > static_cast<unsigned long long>(std::numeric_limits<std::int64_t>::max())) {
    return std::nullopt;
  }
  return std::chrono::microseconds(static_cast<std::int64_t>(*usec));
}

std::optional<std::chrono::microseconds> WatchdogInterval() {
  return WatchdogInterval(std::getenv("WATCHDOG_USEC"), std::getenv("WATCHDOG_PID"), ::getpid());
}

}  // namespace h4::cam

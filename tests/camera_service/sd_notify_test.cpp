// The systemd notification protocol against a real AF_UNIX datagram socket standing in for
// the service manager: what arrives is exactly what systemd would read, for path and
// abstract socket names, and the watchdog period is read as systemd sets it.
#include "firmware/service/sd_notify.h"

#include <array>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace h4::cam {
namespace {

// A bound datagram socket playing systemd's part: "/path" or "@abstract" names.
class FakeManager {
 public:
  explicit FakeManager(std::string name) : name_(std::move(name)) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, name_.data(), name_.size());
    if (name_.front() == '@') address.sun_path[0] = '\0';
    const auto size = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name_.size());
    bound_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&address), size) == 0;
  }
  ~FakeManager() {
    if (fd_ >= 0) ::close(fd_);
    if (name_.front() == '/') std::filesystem::remove(name_);
  }
  FakeManager(const FakeManager&) = delete;
  FakeManager& operator=(const FakeManager&) = delete;

  bool bound() const { return bound_; }
  const std::string& name() const { return name_; }

  // The next datagram, or "<nothing>" after a second without one.
  std::string Receive() const {
    pollfd pfd{fd_, POLLIN, 0};
    if (::poll(&pfd, 1, 1000) != 1) return "<nothing>";
    std::array<char, 4096> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    return n < 0 ? "<error>" : std::string(buffer.data(), static_cast<std::size_t>(n));
  }

 private:
  std::string name_;
  int fd_ = -1;
  bool bound_ = false;
};

std::string TempSocketPath(const std::string& tag) {
  return (std::filesystem::temp_directory_path() /
          fmt::format("h4-sd-notify-{}-{}.sock", tag, ::getpid()))
      .string();
}

// Sets an environment variable for one test and restores the previous value afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    const char* old = std::getenv(name);
    had_ = old != nullptr;
    if (had_) old_ = old;
    if (value != nullptr) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      ::setenv(name_, old_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  bool had_ = false;
  std::string old_;
};

TEST(SdNotify, SendsStateToThePathSocketNamedByNotifySocket) {
  FakeManager manager(TempSocketPath("path"));
  ASSERT_TRUE(manager.bound()) << manager.name();
  ScopedEnv env("NOTIFY_SOCKET", manager.name().c_str());

  const NotifyResult result = SdNotify("READY=1\nSTATUS=camera open");
  EXPECT_EQ(result.status, NotifyResult::Status::kSent) << result.error;
  EXPECT_EQ(manager.Receive(), "READY=1\nSTATUS=camera open");
}

TEST(SdNotify, ReachesAnAbstractSocketNamedWithAt) {
  FakeManager manager(fmt::format("@h4-sd-notify-test-{}", ::getpid()));
  ASSERT_TRUE(manager.bound()) << manager.name();

  const NotifyResult result = SdNotifyTo(manager.name(), "WATCHDOG=1");
  EXPECT_TRUE(result.sent()) << result.error;
  EXPECT_EQ(manager.Receive(), "WATCHDOG=1");
}

TEST(SdNotify, HelpersSendTheAssignmentsSystemdExpects) {
  FakeManager manager(TempSocketPath("helpers"));
  ASSERT_TRUE(manager.bound()) << manager.name();
  ScopedEnv env("NOTIFY_SOCKET", manager.name().c_str());

  EXPECT_TRUE(NotifyReady().sent());
  EXPECT_EQ(manager.Receive(), "READY=1");
  EXPECT_TRUE(NotifyWatchdog().sent());
  EXPECT_EQ(manager.Receive(), "WATCHDOG=1");
  EXPECT_TRUE(NotifyStopping().sent());
  EXPECT_EQ(manager.Receive(), "STOPPING=1");
  // A newline would start a second assignment: it must arrive as one STATUS line.
  EXPECT_TRUE(NotifyStatus("pose 3\nof 40").sent());
  EXPECT_EQ(manager.Receive(), "STATUS=pose 3 of 40");
}

TEST(SdNotify, IsANoOpWithoutNotifySocket) {
  ScopedEnv env("NOTIFY_SOCKET", nullptr);
  const NotifyResult result = NotifyReady();
  EXPECT_EQ(result.status, NotifyResult::Status::kNoSocket);
  EXPECT_TRUE(result.error.empty());
}

TEST(SdNotify, FailsNamingTheSocketWhenNobodyListens) {
  const std::string missing = TempSocketPath("missing");
  std::filesystem::remove(missing);
  const NotifyResult result = SdNotifyTo(missing, "READY=1");
  EXPECT_EQ(result.status, NotifyResult::Status::kFailed);
  EXPECT_NE(result.error.find(missing), std::string::npos) << result.error;
}

TEST(SdNotify, RejectsRelativeAndOverlongSocketNames) {
  const NotifyResult relative = SdNotifyTo("run/notify", "READY=1");
  EXPECT_EQ(relative.status, NotifyResult::Status::kFailed);
  EXPECT_NE(relative.error.find("absolute path"), std::string::npos) << relative.error;

  const NotifyResult overlong = SdNotifyTo("/" + std::string(200, 'x'), "READY=1");
  EXPECT_EQ(overlong.status, NotifyResult::Status::kFailed);
  EXPECT_NE(overlong.error.find("longer than"), std::string::npos) << overlong.error;
}

TEST(WatchdogInterval, ReadsMicrosecondsForThisProcess) {
  const auto interval = WatchdogInterval("30000000", "4242", 4242);
  ASSERT_TRUE(interval.has_value());
  EXPECT_EQ(interval->count(), 30'000'000);
  // WATCHDOG_PID is optional: without it the period is for whoever reads it.
  const auto no_pid = WatchdogInterval("500000", nullptr, 1);
  ASSERT_TRUE(no_pid.has_value());
  EXPECT_EQ(no_pid->count(), 500'000);
}

TEST(WatchdogInterval, IsAbsentForAnotherProcessOrMalformedValues) {
  EXPECT_FALSE(WatchdogInterval("30000000", "4243", 4242).has_value());
  EXPECT_FALSE(WatchdogInterval(nullptr, nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("0", nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("", nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("30s", nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("-5", nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("99999999999999999999999", nullptr, 4242).has_value());
  EXPECT_FALSE(WatchdogInterval("1000", "pid", 4242).has_value());
}

TEST(WatchdogInterval, ReadsTheEnvironmentSystemdSets) {
  const std::string self = fmt::format("{}", ::getpid());
  ScopedEnv usec("WATCHDOG_USEC", "15000000");
  ScopedEnv pid("WATCHDOG_PID", self.c_str());
  const auto interval = WatchdogInterval();
  ASSERT_TRUE(interval.has_value());
  EXPECT_EQ(interval->count(), 15'000'000);
}

}  // namespace
}  // namespace h4::cam

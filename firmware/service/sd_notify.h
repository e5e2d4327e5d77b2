// systemd's service notification protocol without libsystemd: readiness, watchdog
// keep-alives and status text for h4cam.service (Type=notify, WatchdogSec). The protocol is
// one datagram of newline-separated KEY=VALUE assignments ("READY=1", "WATCHDOG=1",
// "STATUS=...") sent to the AF_UNIX socket named by $NOTIFY_SOCKET (a path, or "@name" for
// the abstract namespace); see sd_notify(3). Outside systemd the variable is unset and every
// call is a harmless no-op, so the same program runs by hand, in tests and as a service.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include <sys/types.h>

namespace h4::cam {

/// Outcome of one notification. Never thrown: a service keeps running when it cannot
/// notify (systemd then restarts it, which is the point of the watchdog).
struct NotifyResult {
  enum class Status {
    kSent,      ///< the datagram went out whole
    kNoSocket,  ///< no $NOTIFY_SOCKET: not started by systemd with Type=notify; nothing sent
    kFailed,    ///< the socket name is invalid or sending failed; `error` says why
  };
  Status status = Status::kNoSocket;
  std::string error;  ///< names the socket and the reason, empty unless kFailed

  bool sent() const { return status == Status::kSent; }
};

/// Sends `state` (e.g. "READY=1\nSTATUS=measuring") to the socket named by $NOTIFY_SOCKET.
NotifyResult SdNotify(std::string_view state);

/// Same, to an explicit socket name: an absolute path or "@abstract-name".
NotifyResult SdNotifyTo(std::string_view socket_name, std::string_view state);

/// "READY=1": start-up finished (the camera is open, LCM is up). With Type=notify systemd
/// considers the service started only after this.
NotifyResult NotifyReady();

/// "WATCHDOG=1": the main loop is alive. Send at least every WatchdogInterval() / 2.
NotifyResult NotifyWatchdog();

/// "STOPPING=1": orderly shutdown has begun.
NotifyResult NotifyStopping();

/// "STATUS=<text>": one line shown by `systemctl status h4cam` (newlines become spaces).
NotifyResult NotifyStatus(std::string_view text);

/// The watchdog period systemd expects (WatchdogSec=), from $WATCHDOG_USEC and
/// $WATCHDOG_PID; nullopt when there is no watchdog or it is meant for another process.
std::optional<std::chrono::microseconds> WatchdogInterval();

/// The same from explicit values (nullptr for an unset variable) and the caller's pid.
/// A missing, zero, malformed or out-of-range WATCHDOG_USEC gives nullopt, and so does a
/// WATCHDOG_PID that is set and differs from `self_pid`.
std::optional<std::chrono::microseconds> WatchdogInterval(const char* watchdog_usec,
                                                          const char* watchdog_pid, pid_t self_pid);

}  // namespace h4::cam

// Bounds how often one kind of warning is logged: a flood of bad messages must not become a
// flood of log lines (or cost the receive loop its time). The caller passes the time, so the
// rule is tested on synthetic times.
#pragma once

#include <chrono>
#include <cstdint>

namespace h4::bus {

class WarningThrottle {
 public:
  using Clock = std::chrono::steady_clock;

  explicit WarningThrottle(Clock::duration interval = std::chrono::seconds(1))
      : interval_(interval) {}

  /// True when a warning may be logged at `now` (the first one, then at most one per
  /// interval); `*suppressed` is then the number of warnings held back since the last one.
  bool Allow(Clock::time_point now, int64_t* suppressed) {
    if (logged_once_ && now - last_ < interval_) {
      ++suppressed_;
      return false;
    }
    *suppressed = suppressed_;
    suppressed_ = 0;
    last_ = now;
    logged_once_ = true;
    return true;
  }

 private:
  Clock::duration interval_;
  Clock::time_point last_{};
  bool logged_once_ = false;
  int64_t suppressed_ = 0;
};

}  // namespace h4::bus

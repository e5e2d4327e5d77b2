// Reading the clocks, the one place it is written: LCM's utime (microseconds since the
// Unix epoch, system clock) and elapsed seconds (steady clock) for reports. Pure code
// takes its time as an argument (periodic_schedule.h); these are for the edges.
#pragma once

#include <chrono>
#include <cstdint>

namespace h4 {

/// A duration in seconds (SI inside; std::chrono at the edges).
template <typename Rep, typename Period>
constexpr double Seconds(std::chrono::duration<Rep, Period> duration) {
  return std::chrono::duration<double>(duration).count();
}

/// Seconds elapsed on the steady clock since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return Seconds(std::chrono::steady_clock::now() - start);
}

/// A system-clock time as LCM's utime, microseconds since the Unix epoch.
inline int64_t UtimeOf(std::chrono::system_clock::time_point time) {
  return std::chrono::duration_cast<std::chrono::microseconds>(time.time_since_epoch()).count();
}

/// Now as LCM's utime.
inline int64_t NowUtime() { return UtimeOf(std::chrono::system_clock::now()); }

}  // namespace h4

// When a periodic job (the simulated robot's joint states and status lines, the camera's
// free-run captures and heartbeat) is due. Pure: the caller passes the time, so the rule is
// tested without a wall clock.
#pragma once

#include <chrono>
#include <optional>

namespace h4 {

/// Slots at start, start + period, start + 2 period, ... where start is the first time
/// asked. A late caller gets one slot, not a burst of the missed ones: after a stall the
/// job resumes on the same grid, at the first slot after `now`.
class PeriodicSchedule {
 public:
  using Clock = std::chrono::steady_clock;

  /// `period` must be positive.
  explicit PeriodicSchedule(Clock::duration period);

  /// True when a slot has come at `now` (always on the first call); the schedule then
  /// moves to the next slot after `now`. Times earlier than a previous call are never due.
  bool Due(Clock::time_point now);

  /// The next slot; empty before the first call to Due.
  std::optional<Clock::time_point> next() const { return next_; }

 private:
  Clock::duration period_;
  std::optional<Clock::time_point> next_;
};

}  // namespace h4

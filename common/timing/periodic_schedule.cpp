#include "common/timing/periodic_schedule.h"

#include <stdexcept>

namespace h4 {

PeriodicSchedule::PeriodicSchedule(Clock::duration period) : period_(period) {
  if (period_ <= Clock::duration::zero()) {
    throw std::invalid_argument("PeriodicSchedule: the period must be positive");
  }
}

bool PeriodicSchedule::Due(Clock::time_point now) {
  if (!next_) next_ = now;
  if (now < *next_) return false;
  // Skip every slot already passed in one step (a stall of hours is not a long loop).
  const auto missed = (now - *next_) / period_;
  *next_ += (missed + 1) * period_;
  return true;
}

}  // namespace h4

// The clock offset of a publisher; see clock_offset.h.
#include "host/campaign/clock_offset.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace h4::host {

void ClockOffset::Add(int64_t sender_utime, int64_t arrival_utime) {
  // One of two positive numbers minus the other cannot overflow; others are no clock.
  if (sender_utime <= 0 || arrival_utime <= 0) return;
  samples_us_.push_back(sender_utime - arrival_utime);
  while (samples_us_.size() > std::max<size_t>(window_, 1)) samples_us_.pop_front();
}

std::optional<double> ClockOffset::seconds() const {
  if (samples_us_.size() < kMinSamples) return std::nullopt;
  const auto [lowest, highest] = std::minmax_element(samples_us_.begin(), samples_us_.end());
  // As doubles: the spread of two int64 offsets can exceed int64.
  const double highest_s = static_cast<double>(*highest) * 1e-6;
  if (highest_s - static_cast<double>(*lowest) * 1e-6 > kMaxSpread_s) return std::nullopt;
  return highest_s;
}

std::string DescribeClockOffset(const std::string& what, double offset_s) {
  return fmt::format("{} are {:.1f} s {} this host's clock", what, std::abs(offset_s),
                     offset_s >= 0 ? "ahead of" : "behind");
}

}  // namespace h4::host

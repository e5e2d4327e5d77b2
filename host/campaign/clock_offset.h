// How far a publisher's clock runs ahead of this host's (issue 27 point 12: a camera clock
// 40 s ahead had every authenticated status dropped as stale, 20 s ahead every measurement
// left unpaired, and neither was named). Estimated from the utimes a periodic publisher
// stamps on its messages against their arrival on this host: each sample is the offset minus
// the delivery delay, so the largest recent sample, the least delayed message, is the best
// estimate. Only a consistent offset is reported: a few samples that agree, so that one
// foreign message with an odd utime does not make a clock look wrong. Pure: the caller passes
// both times, so the rule is tested on synthetic ones.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

namespace h4::host {

class ClockOffset {
 public:
  /// Keeps the `window` latest samples (a few seconds of 1 Hz heartbeats).
  explicit ClockOffset(size_t window = 8) : window_(window) {}

  /// A message stamped `sender_utime` by its publisher arrived at `arrival_utime` (this
  /// host's clock), both us since the epoch.
  void Add(int64_t sender_utime, int64_t arrival_utime);
  /// The publisher's clock minus this host's, s; nullopt until kMinSamples of the recent
  /// samples are there and they agree within kMaxSpread_s.
  std::optional<double> seconds() const;

  static constexpr size_t kMinSamples = 3;
  /// Delivery delays on a loaded host stay far below this; a clock set wrong is off by more.
  static constexpr double kMaxSpread_s = 2.0;

 private:
  size_t window_;
  std::deque<int64_t> samples_us_;
};

/// "<what> are 40.0 s ahead of this host's clock" (or "behind"), for a warning.
std::string DescribeClockOffset(const std::string& what, double offset_s);

}  // namespace h4::host

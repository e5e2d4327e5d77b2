// Messages much older than their publisher's freshest ones (issue 27's flood: joint states
// replayed from an hour-old log, settled at this campaign's pose id, made the campaign take
// the robot for settled before it had moved, so pose 1 was measured in motion and skipped).
// A robot's controller stamps its joint states as it reads its encoders, so among the
// recent messages on a channel the least delayed one (the largest utime minus arrival)
// gives where its clock is now; a message that lags it by more than max_lag is stale,
// whatever the clocks' offset. Pure: the caller passes both times, in us since the epoch.
// Robot channels are unsigned (README.md#who-can-talk-to-the-campaign-and-the-camera-threat-model):
// a forged message with a current stamp is not stale, and a forged one dated in the future
// makes the real ones look stale for `memory` seconds; the key protects the camera's
// channels only.
#pragma once

#include <cstdint>
#include <deque>
#include <utility>

namespace h4::host {

class StaleMessageFilter {
 public:
  explicit StaleMessageFilter(double max_lag_s = 2.0, double memory_s = 5.0)
      : max_lag_us_(static_cast<int64_t>(max_lag_s * 1e6)),
        memory_us_(static_cast<int64_t>(memory_s * 1e6)) {}

  /// Records the message; true when its stamp lags the freshest of the last `memory`
  /// seconds of arrivals by more than `max_lag`.
  bool Stale(int64_t sender_utime, int64_t arrival_utime);

 private:
  int64_t max_lag_us_;
  int64_t memory_us_;
  /// (arrival, sender - arrival) with decreasing offsets: the front is the recent maximum.
  std::deque<std::pair<int64_t, int64_t>> window_;
};

}  // namespace h4::host

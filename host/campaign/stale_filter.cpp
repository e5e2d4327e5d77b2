// See stale_filter.h: a sliding maximum of (sender - arrival) over the recent arrivals.
#include "host/campaign/stale_filter.h"

namespace h4::host {

bool StaleMessageFilter::Stale(int64_t sender_utime, int64_t arrival_utime) {
  const int64_t offset = sender_utime - arrival_utime;
  while (!window_.empty() && window_.front().first < arrival_utime - memory_us_) {
    window_.pop_front();
  }
  const bool stale = !window_.empty() && offset < window_.front().second - max_lag_us_;
  while (!window_.empty() && window_.back().second <= offset) window_.pop_back();
  window_.emplace_back(arrival_utime, offset);
  return stale;
}

}  // namespace h4::host

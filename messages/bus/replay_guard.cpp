// Per-sender replay window; see replay_guard.h.
#include "messages/bus/replay_guard.h"

#include <algorithm>

namespace h4::bus {

ReplayGuard::ReplayGuard(size_t max_senders, int64_t forget_after_us)
    : max_senders_(std::max<size_t>(max_senders, 1)), forget_after_us_(forget_after_us) {}

bool ReplayGuard::Accept(uint64_t sender_id, uint64_t sequence, int64_t now_utime) {
  auto it = senders_.find(sender_id);
  if (it == senders_.end()) {
    ForgetSilentSenders(now_utime);
    if (senders_.size() >= max_senders_) ForgetLeastRecentlyHeard();
    it = senders_.emplace(sender_id, Sender{sequence, 1, now_utime}).first;
    return true;
  }
  if (!AcceptInto(&it->second, sequence)) return false;
  it->second.last_heard_utime = now_utime;
  return true;
}

bool ReplayGuard::AcceptInto(Sender* sender, uint64_t sequence) {
  if (sequence > sender->highest) {
    const uint64_t shift = sequence - sender->highest;
    sender->seen = shift >= kWindow ? 1 : (sender->seen << shift) | 1;
    sender->highest = sequence;
    return true;
  }
  const uint64_t behind = sender->highest - sequence;
  if (behind >= kWindow) return false;  // too old to tell: refused, as a replay would be
  const uint64_t bit = uint64_t{1} << behind;
  if ((sender->seen & bit) != 0) return false;
  sender->seen |= bit;
  return true;
}

void ReplayGuard::ForgetSilentSenders(int64_t now_utime) {
  if (forget_after_us_ < 0) return;
  for (auto it = senders_.begin(); it != senders_.end();) {
    it = now_utime - it->second.last_heard_utime > forget_after_us_ ? senders_.erase(it)
                                                                    : std::next(it);
  }
}

void ReplayGuard::ForgetLeastRecentlyHeard() {
  const auto oldest =
      std::min_element(senders_.begin(), senders_.end(), [](const auto& a, const auto& b) {
        return a.second.last_heard_utime < b.second.last_heard_utime;
      });
  if (oldest != senders_.end()) senders_.erase(oldest);
}

}  // namespace h4::bus

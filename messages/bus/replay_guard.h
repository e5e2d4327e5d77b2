// Replay protection of authenticated messages (message_auth.h): per sender, the sequence
// numbers already accepted. A sender (one publishing process, named by a random 64-bit id
// chosen when it starts) numbers its messages 1, 2, 3...; a number is accepted once, either
// above the highest seen or up to kWindow below it (a datagram overtaken by a later one, as
// IPsec's anti-replay window, RFC 4303 section 3.4.3). A restarted sender has a new id, so
// its new numbering is accepted; its old id is forgotten once none of its messages can still
// pass the freshness check (MessageAuthenticator), so the table stays small.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>

namespace h4::bus {

class ReplayGuard {
 public:
  /// Numbers accepted below the highest one seen of a sender (reordering tolerated).
  static constexpr uint64_t kWindow = 64;

  /// Remembers at most `max_senders` senders (the least recently heard is forgotten first)
  /// and forgets a sender not heard for `forget_after_us` microseconds (< 0: never).
  ReplayGuard(size_t max_senders, int64_t forget_after_us);

  /// True (and remembered) when `sequence` of `sender_id` was not accepted before and is
  /// within the window; `now_utime` is the receiver's clock. Call only for messages whose
  /// MAC is verified: only then may they change the state.
  bool Accept(uint64_t sender_id, uint64_t sequence, int64_t now_utime);

  size_t sender_count() const { return senders_.size(); }

 private:
  struct Sender {
    uint64_t highest = 0;  ///< the highest sequence accepted
    uint64_t seen = 0;     ///< bit k: highest - k accepted
    int64_t last_heard_utime = 0;
  };
  void ForgetSilentSenders(int64_t now_utime);
  void ForgetLeastRecentlyHeard();
  static bool AcceptInto(Sender* sender, uint64_t sequence);

  size_t max_senders_;
  int64_t forget_after_us_;
  std::map<uint64_t, Sender> senders_;
};

}  // namespace h4::bus

// Authenticated messages on the bus (off by default; messages/README.md#authenticated-messages). An
// authenticated channel carries the LCM-encoded message followed by a 68-byte trailer, all integers
// big-endian:
//
//   offset  0  "H4A1"        magic and version
//           4  key id        8 bytes: the first 8 of HMAC-SHA256(key, "h4 key id")
//          12  sender id     8 bytes, random, drawn when the publishing process starts
//          20  sequence      uint64, 1, 2, 3... per sender
//          28  utime         int64, the sender's clock at publication [us since the epoch]
//          36  MAC           HMAC-SHA256(key, u32 channel length, channel, u32 message
//                            length, message, trailer bytes 0..35)
//
// A receiver accepts a message only when the trailer is there, the key id is its own, the
// MAC verifies (compared in constant time), the utime is within max_clock_offset_s of its own
// clock and the (sender, sequence) pair was not accepted before (replay_guard.h). The channel
// is inside the MAC, so a message cannot be replayed onto another channel.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "messages/bus/auth_key.h"
#include "messages/bus/hmac_sha256.h"
#include "messages/bus/replay_guard.h"

namespace h4::bus {

inline constexpr size_t kAuthTrailerBytes = 68;

struct AuthOptions {
  /// The channels whose messages are authenticated: those between h4cam and h4cal. The
  /// robot controller's channels (H4_JOINT_STATE, H4_ROBOT_TARGET) and the simulation's are
  /// not, by default: a third-party controller cannot sign.
  std::vector<std::string> channels = {"H4_BOARD_POSE", "H4_BOARD_CORNERS", "H4_CAPTURE_REQUEST",
                                       "H4_CAMERA_STATUS"};
  /// [s] Largest difference accepted between a message's utime and the receiver's clock:
  /// the two hosts' clocks must agree this well (NTP); a recorded message is refused once
  /// this old, even by a receiver that never saw it (one started later).
  double max_clock_offset_s = 30.0;
  /// False only to read a recorded log (collect --from-log), whose messages are old by
  /// definition: MAC, key and sequence are still checked.
  bool check_freshness = true;
  /// Senders (publishing processes) remembered at once; only key holders create senders.
  int max_senders = 64;

  /// False (with `why` naming the field) when a value is out of range.
  bool IsValid(std::string* why) const;
};

/// True when the last kAuthTrailerBytes of the `size` bytes at `data` start with the
/// trailer's magic (whatever the rest: nothing is verified).
bool HasAuthTrailer(const void* data, size_t size);

/// Why a message was accepted or dropped.
/// Named by ToString, in this order (message_auth.cpp).
enum class AuthVerdict {
  kAccepted,
  kUnauthenticated,  ///< no trailer (shorter than one, or no magic)
  kForeignKey,       ///< signed with another key (key id differs)
  kForged,           ///< key id ours, MAC wrong: altered, or forged
  kStale,            ///< utime outside the clock window
  kReplayed,         ///< (sender, sequence) already accepted, or older than the window
};
const char* ToString(AuthVerdict verdict);

class MessageAuthenticator {
 public:
  /// Throws std::invalid_argument when the key is shorter than kMinAuthKeyBytes or the
  /// options are not valid. The sender id is drawn from OpenSSL's generator.
  MessageAuthenticator(const AuthKey& key, AuthOptions options);
  /// The same with a given sender id (tests).
  MessageAuthenticator(const AuthKey& key, AuthOptions options, uint64_t sender_id);

  /// True when messages of `channel` are authenticated.
  bool Covers(const std::string& channel) const;

  /// `size` bytes of an encoded message followed by its trailer, stamped `now_utime`.
  std::vector<uint8_t> Seal(const std::string& channel, const void* message, size_t size,
                            int64_t now_utime);

  /// Checks a received message of `size` bytes at `data` on `channel` against the
  /// receiver's clock `now_utime`; when kAccepted, `*message_size` is the size of the
  /// encoded message before the trailer. Only an accepted message changes the state. When
  /// the MAC verifies (accepted, stale or replayed) and `sender_utime` is given, it receives
  /// the utime the sender sealed the message with: a stale message's tells how far the
  /// sender's clock is off.
  AuthVerdict Open(const std::string& channel, const void* data, size_t size, int64_t now_utime,
                   size_t* message_size, int64_t* sender_utime = nullptr);

  uint64_t sender_id() const { return sender_id_; }
  const AuthOptions& options() const { return options_; }

 private:
  HmacSha256Digest Mac(const std::string& channel, const uint8_t* message, size_t size,
                       const uint8_t* trailer) const;
  bool Fresh(int64_t utime, int64_t now_utime) const;

  std::vector<uint8_t> key_;
  std::array<uint8_t, 8> key_id_{};
  AuthOptions options_;
  uint64_t sender_id_ = 0;
  uint64_t next_sequence_ = 1;
  ReplayGuard guard_;
};

}  // namespace h4::bus

// A thin adapter over lcm::LCM shared by h4cam and h4cal: the URL rule (--lcm-url, else
// $LCM_DEFAULT_URL, else udpm with ttl=0 so nothing leaves the machine), typed
// subscriptions, publish, and handle() with a timeout. Tests use the in-process "memq://"
// provider: real LCM encoding and dispatch without a network.
//
// Whatever arrives on the wire, nothing is thrown out of the receive loop: each message is
// checked against its type's layout and the size limits (wire_check.h) before lcm-gen's
// decode() runs, and what fails is counted per channel and logged at most once a second.
// No exception may unwind through LCM's C code either: it skips LCM's own clean-up (the
// `in_handle` flag, the receive buffer's release), and the next handle() aborts the process
// on an assertion (lcm.c: `!lcm->in_handle`; see messages/README.md).
// So an exception from a handler (e.g. a full disk under the dataset journal) is caught at
// the callback and rethrown by Handle() once LCM has returned.
//
// With a BusAuth (off by default), the messages of its channels are sealed on publish and
// opened on receipt (message_auth.h): what is not authentic is counted and dropped before
// the layout check, like a message that does not decode.
#pragma once

#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "messages/bus/message_auth.h"
#include "messages/bus/warning_throttle.h"
#include "messages/bus/wire_check.h"
#include "messages/bus/wire_layouts.h"

namespace h4::bus {

/// The default when neither --lcm-url nor $LCM_DEFAULT_URL is given: LCM's default group,
/// ttl=0 (nothing leaves the machine; see h4cam.service for ttl=1 on an isolated camera network).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// `url` if not empty, else $LCM_DEFAULT_URL if set and not empty, else kDefaultLcmUrl.
std::string ResolveLcmUrl(const std::string& url);

/// Message authentication of a bus: the pre-shared key and which channels it covers.
struct BusAuth {
  AuthKey key;
  AuthOptions options;
};

/// The authentication of the key file at `key_path` with `options`; nullopt (off) when
/// `key_path` is empty. Throws std::runtime_error naming the file (ReadAuthKeyFile).
std::optional<BusAuth> BusAuthFromKeyFile(const std::string& key_path, AuthOptions options = {});

/// Decodes `size` bytes as Msg after checking them against Msg's layout and `limits`;
/// nullopt (with `why`) when they are not a valid Msg. Never throws on any input.
template <class Msg>
std::optional<Msg> DecodeMessage(const void* data, size_t size, const WireLimits& limits,
                                 std::string* why) {
  if (!CheckEncodedMessage(data, size, LayoutOf<Msg>(), limits, why)) return std::nullopt;
  Msg msg;
  try {
    if (msg.decode(data, 0, static_cast<int>(size)) != static_cast<int>(size)) {
      *why = "lcm-gen's decode refused it";
      return std::nullopt;
    }
  } catch (const std::exception& e) {
    // Unreachable after the layout check; kept so that a layout mistake cannot crash.
    *why = std::string("lcm-gen's decode threw: ") + e.what();
    return std::nullopt;
  }
  return msg;
}

class LcmBus {
 public:
  static constexpr int kMaxMessagesPerHandle = 256;

  /// Connects to ResolveLcmUrl(url); good() is false (error() says why) when LCM fails.
  /// Received messages are checked against `limits` (must be IsValid()). With `auth`, the
  /// messages of its channels are authenticated both ways (throws std::invalid_argument
  /// when its key or options are not valid).
  explicit LcmBus(const std::string& url, WireLimits limits = {},
                  std::optional<BusAuth> auth = std::nullopt);
  LcmBus(const LcmBus&) = delete;
  LcmBus& operator=(const LcmBus&) = delete;

  bool good() const { return lcm_.good(); }
  const std::string& url() const { return url_; }
  std::string error() const;
  lcm::LCM& lcm() { return lcm_; }

  /// Calls `handler` with each message of `channel` that decodes as Msg; a message that
  /// does not (wrong type, truncated, lengths out of limits) is counted, logged and dropped.
  /// An exception from `handler` is rethrown by Handle().
  template <class Msg>
  void Subscribe(const std::string& channel, std::function<void(const Msg&)> handler) {
    SubscribeRaw(channel,
                 [channel, handler = std::move(handler), this](const void* data, uint32_t size) {
                   if (!Authentic(channel, data, &size)) return;
                   std::string why;
                   const std::optional<Msg> msg = DecodeReceived<Msg>(channel, data, size, &why);
                   if (!msg) {
                     OnDecodeFailure(channel, LayoutOf<Msg>().type_name, size, why);
                     return;
                   }
                   handler(*msg);
                 });
  }

  /// Encodes (and seals, on an authenticated channel) and publishes; false (logged) when
  /// LCM refuses.
  template <class Msg>
  bool Publish(const std::string& channel, const Msg& msg) {
    std::vector<uint8_t> encoded(static_cast<size_t>(msg.getEncodedSize()));
    if (msg.encode(encoded.data(), 0, static_cast<int>(encoded.size())) < 0) {
      OnPublishFailure(channel);
      return false;
    }
    return PublishEncoded(channel, encoded);
  }

  /// Dispatches the messages that arrive within `timeout` (0: only those already
  /// queued), at most kMaxMessagesPerHandle: returns the number handled, or -1 when LCM
  /// reports an error. Rethrows the first exception a handler threw (after LCM returned).
  int Handle(std::chrono::milliseconds timeout);

  /// Messages dropped because they did not decode, in all and on one channel.
  int64_t decode_failures() const { return decode_failures_; }
  int64_t decode_failures(const std::string& channel) const;
  int64_t publish_failures() const { return publish_failures_; }

  /// True when messages of `channel` are authenticated on this bus.
  bool authenticates(const std::string& channel) const;
  /// Messages dropped as not authentic: in all, on one channel, for one reason.
  int64_t auth_failures() const { return auth_failures_; }
  int64_t auth_failures(const std::string& channel) const;
  int64_t auth_failures(AuthVerdict verdict) const;
  /// Messages of `channel` signed by a sender with a key and read here unchecked (this bus
  /// has no key for it): the sender authenticates and this end does not, so what this end
  /// publishes to it is refused there (a key on one end only).
  int64_t unchecked_signed(const std::string& channel) const;
  /// Authentic messages of `channel` dropped as stale, and how far ahead of this host's
  /// clock (s, negative: behind) the last one was sealed: a sender whose clock is off by
  /// more than AuthOptions::max_clock_offset_s has every message dropped so.
  int64_t stale_messages(const std::string& channel) const;
  std::optional<double> stale_clock_offset_s(const std::string& channel) const;
  /// The authentication's clock window, s (0 without authentication).
  double max_clock_offset_s() const;

 private:
  using RawHandler = std::function<void(const void* data, uint32_t size)>;
  struct Subscription {
    RawHandler handler;
    LcmBus* bus = nullptr;
    // A plain function for lcm::LCM::subscribeFunction, not a member function: GCC 12
    // miscompiles LCM's pointer-to-member dispatch under -fsanitize=vptr (the sanitizer
    // pass; see cmake/H4Sanitizers.cmake).
    static void Receive(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                        Subscription* self);
  };
  void SubscribeRaw(const std::string& channel, RawHandler handler);
  /// DecodeMessage, and on a channel this bus does not authenticate, a message signed by a
  /// sender that does is read without its trailer, unchecked: without the key nothing can be
  /// checked, and a signed campaign's log still replays into a listener without it.
  template <class Msg>
  std::optional<Msg> DecodeReceived(const std::string& channel, const void* data, uint32_t size,
                                    std::string* why) const {
    std::optional<Msg> msg = DecodeMessage<Msg>(data, size, limits_, why);
    if (!msg && !authenticates(channel) && HasAuthTrailer(data, size)) {
      msg = DecodeMessage<Msg>(data, size - kAuthTrailerBytes, limits_, why);
      if (msg) ++unchecked_signed_by_channel_[channel];
    }
    return msg;
  }
  bool PublishEncoded(const std::string& channel, const std::vector<uint8_t>& encoded);
  /// True when the message may be decoded: `channel` is not authenticated, or the message
  /// is authentic (`*size` then excludes the trailer). Otherwise counted, logged, false.
  bool Authentic(const std::string& channel, const void* data, uint32_t* size);
  /// `sender_utime`: the sealed utime of a message whose MAC verified (else nullopt).
  void OnAuthFailure(const std::string& channel, uint32_t size, AuthVerdict verdict,
                     std::optional<int64_t> sender_utime);
  void OnDecodeFailure(const std::string& channel, const char* type, uint32_t size,
                       const std::string& why);
  void OnPublishFailure(const std::string& channel);

  struct ChannelFailures {
    int64_t count = 0;
    WarningThrottle throttle;
    int64_t stale = 0;                     ///< of them, kStale
    std::optional<double> stale_offset_s;  ///< the last stale one's sealed utime - now, s
  };

  std::string url_;
  WireLimits limits_;
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  std::exception_ptr handler_exception_;        ///< thrown by a handler, rethrown by Handle()
  std::unique_ptr<MessageAuthenticator> auth_;  ///< null: no authentication (the default)
  std::map<std::string, ChannelFailures> decode_failures_by_channel_;
  std::map<std::string, ChannelFailures> auth_failures_by_channel_;
  /// Counted by the const DecodeReceived, which the receive path calls.
  mutable std::map<std::string, int64_t> unchecked_signed_by_channel_;
  std::map<AuthVerdict, int64_t> auth_failures_by_verdict_;
  int64_t auth_failures_ = 0;
  int64_t decode_failures_ = 0;
  int64_t publish_failures_ = 0;
};

}  // namespace h4::bus

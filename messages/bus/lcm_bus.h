// A thin adapter over lcm::LCM shared by h4cam and h4cal: the URL rule (--lcm-url, else
// $LCM_DEFAULT_URL, else udpm with ttl=0 so nothing leaves the machine), typed
// subscriptions whose decode failures are counted and logged instead of thrown, publish,
// and handle() with a timeout. Tests use the in-process "memq://" provider: real LCM
// encoding and dispatch without a network.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

namespace h4::bus {

/// The default when neither --lcm-url nor $LCM_DEFAULT_URL is given: LCM's default group,
/// ttl=0 (nothing leaves the machine; see h4cam.service for ttl=1 on an isolated camera network).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// `url` if not empty, else $LCM_DEFAULT_URL if set and not empty, else kDefaultLcmUrl.
std::string ResolveLcmUrl(const std::string& url);

class LcmBus {
 public:
  static constexpr int kMaxMessagesPerHandle = 256;

  /// Connects to ResolveLcmUrl(url); good() is false (error() says why) when LCM fails.
  explicit LcmBus(const std::string& url);
  LcmBus(const LcmBus&) = delete;
  LcmBus& operator=(const LcmBus&) = delete;

  bool good() const { return lcm_.good(); }
  const std::string& url() const { return url_; }
  std::string error() const;
  lcm::LCM& lcm() { return lcm_; }

  /// Calls `handler` with each message of `channel` that decodes as Msg; a message that
  /// does not decode (wrong type, truncated) is counted and logged, and dropped.
  template <class Msg>
  void Subscribe(const std::string& channel, std::function<void(const Msg&)> handler) {
    SubscribeRaw(channel,
                 [channel, handler = std::move(handler), this](const void* data, uint32_t size) {
                   Msg msg;
                   if (msg.decode(data, 0, static_cast<int>(size)) < 0) {
                     OnDecodeFailure(channel, Msg::getTypeName(), size);
                     return;
                   }
                   handler(msg);
                 });
  }

  /// Encodes and publishes; false (logged) when LCM refuses.
  template <class Msg>
  bool Publish(const std::string& channel, const Msg& msg) {
    const int ret = lcm_.publish(channel, &msg);
    if (ret != 0) OnPublishFailure(channel);
    return ret == 0;
  }

  /// Dispatches the messages that arrive within `timeout` (0: only those already
  /// queued), at most kMaxMessagesPerHandle: returns the number handled, or -1 when LCM
  /// reports an error.
  int Handle(std::chrono::milliseconds timeout);

  int64_t decode_failures() const { return decode_failures_; }
  int64_t publish_failures() const { return publish_failures_; }

 private:
  using RawHandler = std::function<void(const void* data, uint32_t size)>;
  struct Subscription {
    RawHandler handler;
    // A plain function for lcm::LCM::subscribeFunction, not a member function: GCC 12
    // miscompiles LCM's pointer-to-member dispatch under -fsanitize=vptr (the sanitizer
    // pass; see cmake/H4Sanitizers.cmake).
    static void Receive(const lcm::ReceiveBuffer* rbuf, const std::string& channel,
                        Subscription* self);
  };
  void SubscribeRaw(const std::string& channel, RawHandler handler);
  void OnDecodeFailure(const std::string& channel, const char* type, uint32_t size);
  void OnPublishFailure(const std::string& channel);

  std::string url_;
  lcm::LCM lcm_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  int64_t decode_failures_ = 0;
  int64_t publish_failures_ = 0;
};

}  // namespace h4::bus

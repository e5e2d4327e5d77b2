// The LCM adapter shared by both programs; see lcm_bus.h.
#include "messages/bus/lcm_bus.h"

#include <cstdlib>

#include <spdlog/spdlog.h>

namespace h4::bus {

std::string ResolveLcmUrl(const std::string& url) {
  if (!url.empty()) return url;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && env[0] != '\0') {
    return env;
  }
  return kDefaultLcmUrl;
}

LcmBus::LcmBus(const std::string& url) : url_(ResolveLcmUrl(url)), lcm_(url_) {}

std::string LcmBus::error() const {
  return good() ? std::string() : "lcm: cannot open '" + url_ + "' (bad URL or no multicast route)";
}

void LcmBus::Subscription::Receive(const lcm::ReceiveBuffer* rbuf, const std::string&,
                                   Subscription* self) {
  self->handler(rbuf->data, rbuf->data_size);
}

void LcmBus::SubscribeRaw(const std::string& channel, RawHandler handler) {
  subscriptions_.push_back(std::make_unique<Subscription>(Subscription{std::move(handler)}));
  lcm_.subscribeFunction(channel, &Subscription::Receive, subscriptions_.back().get());
}

int LcmBus::Handle(std::chrono::milliseconds timeout) {
  if (!good()) return -1;
  int handled = 0;
  // handleTimeout dispatches one message at a time: drain what is queued, waiting at
  // most `timeout` for the first. The drain is bounded so that a flood (or handlers slower
  // than the arrival rate) cannot keep the caller from its other work.
  int wait_ms = static_cast<int>(timeout.count());
  for (;;) {
    if (handled >= kMaxMessagesPerHandle) return handled;
    const int ret = lcm_.handleTimeout(wait_ms);
    if (ret < 0) return handled > 0 ? handled : -1;
    if (ret == 0) return handled;
    ++handled;
    wait_ms = 0;
  }
}

void LcmBus::OnDecodeFailure(const std::string& channel, const char* type, uint32_t size) {
  ++decode_failures_;
  spdlog::warn("lcm: dropped a message of {} bytes on {}: does not decode as {} ({} so far)", size,
               channel, type, decode_failures_);
}

void LcmBus::OnPublishFailure(const std::string& channel) {
  ++publish_failures_;
  spdlog::warn("lcm: cannot publish on {} ({} failures so far)", channel, publish_failures_);
}

}  // namespace h4::bus

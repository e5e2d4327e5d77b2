// The LCM adapter shared by both programs; see lcm_bus.h.
#include "messages/bus/lcm_bus.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include <spdlog/spdlog.h>

#include "common/timing/clock.h"

namespace h4::bus {

std::string ResolveLcmUrl(const std::string& url) {
  if (!url.empty()) return url;
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env != nullptr && env[0] != '\0') {
    return env;
  }
  return kDefaultLcmUrl;
}

std::optional<BusAuth> BusAuthFromKeyFile(const std::string& key_path, AuthOptions options) {
  if (key_path.empty()) return std::nullopt;
  return BusAuth{ReadAuthKeyFile(key_path), std::move(options)};
}

LcmBus::LcmBus(const std::string& url, WireLimits limits, std::optional<BusAuth> auth)
    : url_(ResolveLcmUrl(url)), limits_(limits), lcm_(url_) {
  std::string why;
  if (!limits_.IsValid(&why)) throw std::invalid_argument(why);
  if (auth) auth_ = std::make_unique<MessageAuthenticator>(auth->key, std::move(auth->options));
}

std::string LcmBus::error() const {
  return good() ? std::string() : "lcm: cannot open '" + url_ + "' (bad URL or no multicast route)";
}

void LcmBus::Subscription::Receive(const lcm::ReceiveBuffer* rbuf, const std::string&,
                                   Subscription* self) {
  // Called from LCM's C code: nothing may unwind through it (see lcm_bus.h). Handlers after
  // a failed one still run; the first exception wins.
  try {
    self->handler(rbuf->data, rbuf->data_size);
  } catch (...) {
    if (!self->bus->handler_exception_) self->bus->handler_exception_ = std::current_exception();
  }
}

void LcmBus::SubscribeRaw(const std::string& channel, RawHandler handler) {
  subscriptions_.push_back(std::make_unique<Subscription>(Subscription{std::move(handler), this}));
  lcm_.subscribeFunction(channel, &Subscription::Receive, subscriptions_.back().get());
}

bool LcmBus::PublishEncoded(const std::string& channel, const std::vector<uint8_t>& encoded) {
  int ret = 0;
  if (authenticates(channel)) {
    const std::vector<uint8_t> sealed =
        auth_->Seal(channel, encoded.data(), encoded.size(), NowUtime());
    ret = lcm_.publish(channel, sealed.data(), static_cast<unsigned>(sealed.size()));
  } else {
    ret = lcm_.publish(channel, encoded.data(), static_cast<unsigned>(encoded.size()));
  }
  if (ret != 0) OnPublishFailure(channel);
  return ret == 0;
}

bool LcmBus::authenticates(const std::string& channel) const {
  return auth_ != nullptr && auth_->Covers(channel);
}

bool LcmBus::Authentic(const std::string& channel, const void* data, uint32_t* size) {
  if (!authenticates(channel)) return true;
  size_t message_size = 0;
  int64_t sender_utime = 0;
  const int64_t now_utime = NowUtime();
  const AuthVerdict verdict =
      auth_->Open(channel, data, *size, now_utime, &message_size, &sender_utime);
  if (verdict != AuthVerdict::kAccepted) {
    OnAuthFailure(
        channel, *size, verdict,
        verdict == AuthVerdict::kStale ? std::optional<int64_t>(sender_utime) : std::nullopt);
    return false;
  }
  *size = static_cast<uint32_t>(message_size);
  return true;
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
    if (handler_exception_) std::rethrow_exception(std::exchange(handler_exception_, nullptr));
    if (ret < 0) return handled > 0 ? handled : -1;
    if (ret == 0) return handled;
    ++handled;
    wait_ms = 0;
  }
}

int64_t LcmBus::decode_failures(const std::string& channel) const {
  const auto it = decode_failures_by_channel_.find(channel);
  return it == decode_failures_by_channel_.end() ? 0 : it->second.count;
}

int64_t LcmBus::unchecked_signed(const std::string& channel) const {
  const auto it = unchecked_signed_by_channel_.find(channel);
  return it == unchecked_signed_by_channel_.end() ? 0 : it->second;
}

void LcmBus::OnDecodeFailure(const std::string& channel, const char* type, uint32_t size,
                             const std::string& why) {
  ++decode_failures_;
  ChannelFailures& failures = decode_failures_by_channel_[channel];
  ++failures.count;
  int64_t suppressed = 0;
  if (!failures.throttle.Allow(WarningThrottle::Clock::now(), &suppressed)) return;
  spdlog::warn("lcm: dropped a message of {} bytes on {}: not a valid {}: {} ({} on {} so far{})",
               size, channel, type, why, failures.count, channel,
               suppressed > 0 ? fmt::format(", {} not logged", suppressed) : std::string());
}

int64_t LcmBus::auth_failures(const std::string& channel) const {
  const auto it = auth_failures_by_channel_.find(channel);
  return it == auth_failures_by_channel_.end() ? 0 : it->second.count;
}

int64_t LcmBus::auth_failures(AuthVerdict verdict) const {
  const auto it = auth_failures_by_verdict_.find(verdict);
  return it == auth_failures_by_verdict_.end() ? 0 : it->second;
}

int64_t LcmBus::stale_messages(const std::string& channel) const {
  const auto it = auth_failures_by_channel_.find(channel);
  return it == auth_failures_by_channel_.end() ? 0 : it->second.stale;
}

std::optional<double> LcmBus::stale_clock_offset_s(const std::string& channel) const {
  const auto it = auth_failures_by_channel_.find(channel);
  return it == auth_failures_by_channel_.end() ? std::nullopt : it->second.stale_offset_s;
}

double LcmBus::max_clock_offset_s() const {
  return auth_ != nullptr ? auth_->options().max_clock_offset_s : 0.0;
}

void LcmBus::OnAuthFailure(const std::string& channel, uint32_t size, AuthVerdict verdict,
                           std::optional<int64_t> sender_utime) {
  ++auth_failures_;
  ++auth_failures_by_verdict_[verdict];
  ChannelFailures& failures = auth_failures_by_channel_[channel];
  ++failures.count;
  std::string clock;
  if (sender_utime) {
    // An authentic message refused for its time alone: the sender's clock is off (or the
    // message is a late replay; a clock off stays so message after message).
    ++failures.stale;
    const double offset_s =
        (static_cast<double>(*sender_utime) - static_cast<double>(NowUtime())) * 1e-6;
    failures.stale_offset_s = offset_s;
    clock = fmt::format(
        ": sealed {:.1f} s {} this host's clock (window {:.0f} s): check "
        "NTP/chrony on both hosts",
        std::abs(offset_s), offset_s >= 0 ? "ahead of" : "behind", max_clock_offset_s());
  }
  int64_t suppressed = 0;
  if (!failures.throttle.Allow(WarningThrottle::Clock::now(), &suppressed)) return;
  spdlog::warn("lcm: dropped a message of {} bytes on {}: {}{} ({} on {} so far{})", size, channel,
               ToString(verdict), clock, failures.count, channel,
               suppressed > 0 ? fmt::format(", {} not logged", suppressed) : std::string());
}

void LcmBus::OnPublishFailure(const std::string& channel) {
  ++publish_failures_;
  spdlog::warn("lcm: cannot publish on {} ({} failures so far)", channel, publish_failures_);
}

}  // namespace h4::bus

// The authenticated-message trailer; see message_auth.h for its layout and rules.
#include "messages/bus/message_auth.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <fmt/core.h>

#include "common/text/enum_names.h"

namespace h4::bus {
namespace {

constexpr uint8_t kMagic[4] = {'H', '4', 'A', '1'};
constexpr size_t kKeyIdOffset = 4;
constexpr size_t kSenderOffset = 12;
constexpr size_t kSequenceOffset = 20;
constexpr size_t kUtimeOffset = 28;
constexpr size_t kMacOffset = 36;
static_assert(kMacOffset + kHmacSha256Bytes == kAuthTrailerBytes);

void PutU64(uint8_t* out, uint64_t value) {
  for (int i = 7; i >= 0; --i, value >>= 8) out[i] = static_cast<uint8_t>(value & 0xff);
}
uint64_t GetU64(const uint8_t* in) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | in[i];
  return value;
}
void AppendU32(std::vector<uint8_t>* out, uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<uint8_t>(value >> shift));
}

std::array<uint8_t, 8> KeyId(const std::vector<uint8_t>& key) {
  static constexpr char kLabel[] = "h4 key id";
  const HmacSha256Digest digest = HmacSha256(key, kLabel, sizeof kLabel - 1);
  std::array<uint8_t, 8> id{};
  std::copy_n(digest.begin(), id.size(), id.begin());
  return id;
}

uint64_t RandomSenderId() {
  uint8_t bytes[8];
  SecureRandomBytes(bytes, sizeof bytes);
  return GetU64(bytes);
}

int64_t ForgetAfterUs(const AuthOptions& options) {
  // A message passes the freshness check at most 2 * max_clock_offset_s after the receiver
  // last heard its sender (its utime may lead the receiver's clock by the offset, and may
  // then be late by the offset): forgetting later than that keeps every replay refused.
  if (!options.check_freshness) return -1;
  return static_cast<int64_t>(std::ceil(3.0 * options.max_clock_offset_s * 1e6));
}

}  // namespace

bool HasAuthTrailer(const void* data, size_t size) {
  return size >= kAuthTrailerBytes &&
         std::memcmp(static_cast<const uint8_t*>(data) + size - kAuthTrailerBytes, kMagic,
                     sizeof kMagic) == 0;
}

bool AuthOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (channels.empty()) return fail("auth: channels: expected at least one channel");
  if (!(max_clock_offset_s > 0) || max_clock_offset_s > 86400) {
    return fail("auth: max_clock_offset_s: expected (0, 86400] s");
  }
  if (max_senders < 1 || max_senders > 100000) return fail("auth: max_senders: expected 1..100000");
  return true;
}

constexpr EnumNames<AuthVerdict, AuthVerdict::kReplayed> kAuthVerdictNames = {
    "accepted",
    "not authenticated",
    "signed with another key",
    "MAC does not verify (altered or forged)",
    "utime outside the clock window (stale or replayed)",
    "sequence already seen (replayed)"};

const char* ToString(AuthVerdict verdict) { return kAuthVerdictNames.NameOf(verdict); }

MessageAuthenticator::MessageAuthenticator(const AuthKey& key, AuthOptions options)
    : MessageAuthenticator(key, std::move(options), RandomSenderId()) {}

MessageAuthenticator::MessageAuthenticator(const AuthKey& key, AuthOptions options,
                                           uint64_t sender_id)
    : key_(key.bytes),
      options_(std::move(options)),
      sender_id_(sender_id),
      guard_(static_cast<size_t>(std::max(options_.max_senders, 1)), ForgetAfterUs(options_)) {
  if (key_.size() < kMinAuthKeyBytes) {
    throw std::invalid_argument(fmt::format("{}: auth key of {} bytes; expected at least {}",
                                            key.source, key_.size(), kMinAuthKeyBytes));
  }
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument(why);
  key_id_ = KeyId(key_);
}

bool MessageAuthenticator::Covers(const std::string& channel) const {
  return std::find(options_.channels.begin(), options_.channels.end(), channel) !=
         options_.channels.end();
}

HmacSha256Digest MessageAuthenticator::Mac(const std::string& channel, const uint8_t* message,
                                           size_t size, const uint8_t* trailer) const {
  std::vector<uint8_t> input;
  input.reserve(8 + channel.size() + size + kMacOffset);
  AppendU32(&input, static_cast<uint32_t>(channel.size()));
  input.insert(input.end(), channel.begin(), channel.end());
  AppendU32(&input, static_cast<uint32_t>(size));
  input.insert(input.end(), message, message + size);
  input.insert(input.end(), trailer, trailer + kMacOffset);
  return HmacSha256(key_, input.data(), input.size());
}

std::vector<uint8_t> MessageAuthenticator::Seal(const std::string& channel, const void* message,
                                                size_t size, int64_t now_utime) {
  const auto* bytes = static_cast<const uint8_t*>(message);
  std::vector<uint8_t> sealed(size + kAuthTrailerBytes);
  if (size > 0) std::memcpy(sealed.data(), bytes, size);
  uint8_t* trailer = sealed.data() + size;
  std::memcpy(trailer, kMagic, sizeof kMagic);
  std::copy(key_id_.begin(), key_id_.end(), trailer + kKeyIdOffset);
  PutU64(trailer + kSenderOffset, sender_id_);
  PutU64(trailer + kSequenceOffset, next_sequence_++);
  PutU64(trailer + kUtimeOffset, static_cast<uint64_t>(now_utime));
  const HmacSha256Digest mac = Mac(channel, sealed.data(), size, trailer);
  std::copy(mac.begin(), mac.end(), trailer + kMacOffset);
  return sealed;
}

bool MessageAuthenticator::Fresh(int64_t utime, int64_t now_utime) const {
  if (!options_.check_freshness) return true;
  const double offset_s =
      std::abs(static_cast<double>(now_utime) - static_cast<double>(utime)) * 1e-6;
  return offset_s <= options_.max_clock_offset_s;
}

AuthVerdict MessageAuthenticator::Open(const std::string& channel, const void* data, size_t size,
                                       int64_t now_utime, size_t* message_size,
                                       int64_t* sender_utime) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (size < kAuthTrailerBytes) return AuthVerdict::kUnauthenticated;
  const size_t body_size = size - kAuthTrailerBytes;
  const uint8_t* trailer = bytes + body_size;
  if (std::memcmp(trailer, kMagic, sizeof kMagic) != 0) return AuthVerdict::kUnauthenticated;
  if (std::memcmp(trailer + kKeyIdOffset, key_id_.data(), key_id_.size()) != 0) {
    return AuthVerdict::kForeignKey;
  }
  const HmacSha256Digest mac = Mac(channel, bytes, body_size, trailer);
  if (!ConstantTimeEqual(mac.data(), trailer + kMacOffset, mac.size())) return AuthVerdict::kForged;
  const auto utime = static_cast<int64_t>(GetU64(trailer + kUtimeOffset));
  if (sender_utime != nullptr) *sender_utime = utime;
  if (!Fresh(utime, now_utime)) return AuthVerdict::kStale;
  if (!guard_.Accept(GetU64(trailer + kSenderOffset), GetU64(trailer + kSequenceOffset),
                     now_utime)) {
    return AuthVerdict::kReplayed;
  }
  *message_size = body_size;
  return AuthVerdict::kAccepted;
}

}  // namespace h4::bus

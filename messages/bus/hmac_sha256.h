// HMAC-SHA256 (RFC 2104, FIPS 180-4) and a constant-time comparison, from OpenSSL's
// libcrypto: the message authentication of the bus (message_auth.h) uses nothing else, and
// no cryptography is written here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace h4::bus {

inline constexpr size_t kHmacSha256Bytes = 32;
using HmacSha256Digest = std::array<uint8_t, kHmacSha256Bytes>;

/// HMAC-SHA256 of `size` bytes at `data` under `key` (any length; RFC 2104 hashes a key
/// longer than the block). Throws std::runtime_error only if OpenSSL itself fails.
HmacSha256Digest HmacSha256(const std::vector<uint8_t>& key, const void* data, size_t size);

/// True when the `size` bytes at `a` and `b` are equal, in a time that does not depend on
/// where they differ (OpenSSL's CRYPTO_memcmp), so that a forger learns nothing from timing.
bool ConstantTimeEqual(const void* a, const void* b, size_t size);

/// `size` bytes from OpenSSL's cryptographically secure generator (RAND_bytes); throws
/// std::runtime_error if it is not seeded.
void SecureRandomBytes(void* out, size_t size);

}  // namespace h4::bus

// HMAC-SHA256 through our OpenSSL wrapper (messages/bus/hmac_sha256.h) against the test
// vectors of RFC 4231 (section 4): a wrong digest, key handling or length would fail here.
#include "messages/bus/hmac_sha256.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

namespace h4::bus {
namespace {

std::string Hex(const HmacSha256Digest& digest) {
  std::string hex;
  for (uint8_t byte : digest) {
    char pair[3];
    std::snprintf(pair, sizeof pair, "%02x", byte);
    hex += pair;
  }
  return hex;
}

std::string HmacHex(const std::vector<uint8_t>& key, const std::string& data) {
  return Hex(HmacSha256(key, data.data(), data.size()));
}

TEST(HmacSha256Test, Rfc4231TestCase1) {
  EXPECT_EQ(HmacHex(std::vector<uint8_t>(20, 0x0b), "Hi There"),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
}

TEST(HmacSha256Test, Rfc4231TestCase2KeyShorterThanTheOutput) {
  EXPECT_EQ(HmacHex({'J', 'e', 'f', 'e'}, "what do ya want for nothing?"),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

TEST(HmacSha256Test, Rfc4231TestCase6KeyLongerThanTheBlockIsHashedFirst) {
  EXPECT_EQ(HmacHex(std::vector<uint8_t>(131, 0xaa),
                    "Test Using Larger Than Block-Size Key - Hash Key First"),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST(HmacSha256Test, ConstantTimeEqualTellsEqualFromDifferentAtAnyByte) {
  const HmacSha256Digest a = HmacSha256({1, 2, 3}, "x", 1);
  EXPECT_TRUE(ConstantTimeEqual(a.data(), a.data(), a.size()));
  for (size_t i = 0; i < a.size(); ++i) {
    HmacSha256Digest b = a;
    b[i] ^= 0x01;
    EXPECT_FALSE(ConstantTimeEqual(a.data(), b.data(), a.size())) << "byte " << i;
  }
}

TEST(HmacSha256Test, SecureRandomBytesDifferBetweenDraws) {
  uint8_t a[16] = {}, b[16] = {};
  SecureRandomBytes(a, sizeof a);
  SecureRandomBytes(b, sizeof b);
  EXPECT_FALSE(ConstantTimeEqual(a, b, sizeof a));  // 2^-128 to fail by chance
}

}  // namespace
}  // namespace h4::bus

// Test helpers shared by the bus tests: a message's LCM wire bytes, and a big-endian write
// into them (to forge the lengths and counts a hostile sender would).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace h4::bus::wire_bytes {

template <class Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return bytes;
}

inline void PutBigEndian32(std::vector<uint8_t>* bytes, size_t pos, int32_t value) {
  const auto u = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) (*bytes)[pos + static_cast<size_t>(i)] = uint8_t(u >> (24 - 8 * i));
}

}  // namespace h4::bus::wire_bytes

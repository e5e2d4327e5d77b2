// The layout walk of encoded LCM messages; see wire_check.h.
#include "messages/bus/wire_check.h"

#include <cstring>

#include <fmt/format.h>

namespace h4::bus {
namespace {

uint64_t ReadBigEndian(const uint8_t* p, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value = (value << 8) | p[i];
  return value;
}

int ScalarBytes(WireKind kind) {
  switch (kind) {
    case WireKind::kInt8:
      return 1;
    case WireKind::kInt32:
      return 4;
    case WireKind::kInt64:
      return 8;
    case WireKind::kDouble:
      return 8;
    case WireKind::kString:
      return 0;
  }
  return 0;
}

/// Walks the fields from `pos`; `int32_values[i]` keeps field i's value when it is a scalar
/// int32 (the count of a later variable array).
class Walker {
 public:
  Walker(const uint8_t* data, size_t size, const WireLimits& limits)
      : data_(data), size_(size), limits_(limits) {}

  bool Walk(const WireLayout& layout, std::string* why) {
    if (size_ > limits_.max_message_bytes) {
      *why = fmt::format("{} bytes, more than the {} accepted", size_, limits_.max_message_bytes);
      return false;
    }
    if (size_ < 8 || static_cast<int64_t>(ReadBigEndian(data_, 8)) != layout.hash) {
      *why = "fingerprint is not " + std::string(layout.type_name) + "'s";
      return false;
    }
    pos_ = 8;
    int32_values_.assign(layout.fields.size(), 0);
    for (size_t i = 0; i < layout.fields.size(); ++i) {
      if (!WalkField(layout.fields[i], i, why)) {
        *why = fmt::format("field '{}' at byte {}: {}", layout.fields[i].name, pos_, *why);
        return false;
      }
    }
    if (pos_ != size_) {
      *why = fmt::format("{} bytes after the last field", size_ - pos_);
      return false;
    }
    return true;
  }

 private:
  bool WalkField(const WireField& field, size_t index, std::string* why) {
    int64_t count = field.count;
    if (field.count_field >= 0) {
      count = int32_values_[static_cast<size_t>(field.count_field)];
      const int64_t max_count = field.max_count > 0 ? field.max_count : limits_.max_array_length;
      if (count < 0 || count > max_count) {
        *why = fmt::format("array length {} outside [0, {}]", count, max_count);
        return false;
      }
    }
    for (int64_t k = 0; k < count; ++k) {
      if (field.kind == WireKind::kString ? !SkipString(why) : !SkipScalar(field, index, why)) {
        return false;
      }
    }
    return true;
  }

  bool SkipScalar(const WireField& field, size_t index, std::string* why) {
    const size_t bytes = static_cast<size_t>(ScalarBytes(field.kind));
    if (size_ - pos_ < bytes) {
      *why = "message ends inside it";
      return false;
    }
    if (field.kind == WireKind::kInt32 && field.count == 1 && field.count_field < 0) {
      int32_values_[index] =
          static_cast<int32_t>(static_cast<uint32_t>(ReadBigEndian(data_ + pos_, 4)));
    }
    pos_ += bytes;
    return true;
  }

  bool SkipString(std::string* why) {
    if (size_ - pos_ < 4) {
      *why = "message ends inside the string length";
      return false;
    }
    const int32_t length =
        static_cast<int32_t>(static_cast<uint32_t>(ReadBigEndian(data_ + pos_, 4)));
    pos_ += 4;
    if (length < 1 || length > limits_.max_string_bytes) {
      *why = fmt::format("string length {} outside [1, {}]", length, limits_.max_string_bytes);
      return false;
    }
    if (size_ - pos_ < static_cast<size_t>(length)) {
      *why = fmt::format("string of {} bytes, only {} left", length, size_ - pos_);
      return false;
    }
    const size_t text_bytes = static_cast<size_t>(length) - 1;
    if (data_[pos_ + text_bytes] != 0) {
      *why = "string does not end with NUL";
      return false;
    }
    // lcm-gen's decode keeps an inner NUL, its encode stops there: the string would change.
    if (std::memchr(data_ + pos_, 0, text_bytes) != nullptr) {
      *why = "string holds a NUL before its end";
      return false;
    }
    pos_ += static_cast<size_t>(length);
    return true;
  }

  const uint8_t* data_;
  size_t size_;
  const WireLimits& limits_;
  size_t pos_ = 0;
  std::vector<int64_t> int32_values_;
};

}  // namespace

bool WireLimits::IsValid(std::string* why) const {
  if (max_message_bytes < 8) {
    *why = "WireLimits.max_message_bytes must be at least 8 (the fingerprint)";
    return false;
  }
  if (max_string_bytes < 1) {
    *why = "WireLimits.max_string_bytes must be at least 1 (the NUL)";
    return false;
  }
  if (max_array_length < 0) {
    *why = "WireLimits.max_array_length must not be negative";
    return false;
  }
  return true;
}

bool CheckEncodedMessage(const void* data, size_t size, const WireLayout& layout,
                         const WireLimits& limits, std::string* why) {
  if (data == nullptr && size > 0) {
    *why = "no data";
    return false;
  }
  return Walker(static_cast<const uint8_t*>(data), size, limits).Walk(layout, why);
}

}  // namespace h4::bus

// Checks an encoded LCM message against its type's layout before lcm-gen's decode() reads
// it. The generated C++ decode trusts the lengths on the wire: a string length of 0 or less
// makes it call std::string::assign with (size_t)-1 (std::length_error), INT32_MIN overflows
// `length - 1` (undefined behaviour), and a variable array count is passed to
// std::vector::resize before the buffer is checked (a negative joint_count throws
// std::length_error, a large one allocates gigabytes). This walk reads every length and
// count first, against explicit limits and the bytes actually received, so decode() only
// ever sees messages it can decode without allocating more than the message holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace h4::bus {

/// The scalar and array kinds our .lcm types use (messages/README.md).
enum class WireKind {
  kInt8,    ///< int8_t, and boolean (one byte on the wire)
  kInt32,   ///< int32_t, big-endian
  kInt64,   ///< int64_t, big-endian
  kDouble,  ///< double, big-endian IEEE 754
  kString,  ///< int32 length including the terminating NUL, the bytes, the NUL
};

/// One field of a type, in .lcm order. `count` elements of `kind` (a fixed array), or, when
/// `count_field` >= 0, as many as the int32 field at that index holds (a variable array).
struct WireField {
  const char* name = "";
  WireKind kind = WireKind::kInt8;
  int count = 1;
  int count_field = -1;
  /// A variable array's own bound when > 0 (board_corners_t's corners: a board has more than
  /// WireLimits::max_array_length), else WireLimits::max_array_length.
  int max_count = 0;
};

/// A type's fingerprint (lcm-gen's getHash()) and fields.
struct WireLayout {
  const char* type_name = "";
  int64_t hash = 0;
  std::vector<WireField> fields;
};

/// Limits checked before anything is allocated. The defaults hold every message our
/// programs send with a wide margin; LCM itself accepts messages up to 256 MB.
struct WireLimits {
  size_t max_message_bytes = 64 * 1024;  ///< [bytes] a whole encoded message
  int32_t max_string_bytes = 4096;       ///< [bytes] one string, its NUL included
  int32_t max_array_length = 64;         ///< [-] elements of one variable-length array

  /// False (with `why` naming the field) when a limit is not positive.
  bool IsValid(std::string* why) const;
};

/// True when `data` (`size` bytes) is an encoding of `layout` that lcm-gen's decode() reads
/// without error or excess allocation: the fingerprint matches, every string length is in
/// [1, max_string_bytes] and ends with its only NUL, every array count in
/// [0, max_array_length], and the fields end exactly at `size`. Otherwise false, and `why`
/// names the field.
bool CheckEncodedMessage(const void* data, size_t size, const WireLayout& layout,
                         const WireLimits& limits, std::string* why);

}  // namespace h4::bus

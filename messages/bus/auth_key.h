// The pre-shared key of authenticated messages (message_auth.h): read from a key file that
// only its owner may read, at least kMinAuthKeyBytes long. Make one with
//   (umask 077; head -c 32 /dev/urandom > h4.key)
// and copy it to both ends (messages/README.md#authenticated-messages).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace h4::bus {

inline constexpr size_t kMinAuthKeyBytes = 32;    ///< HMAC-SHA256's output size (RFC 2104 §3)
inline constexpr size_t kMaxAuthKeyBytes = 4096;  ///< a key file, not a stray large file

struct AuthKey {
  std::vector<uint8_t> bytes;
  std::string source;  ///< where it came from (a path), for messages
};

/// Reads `path` whole as the key. Throws std::runtime_error naming the file when it is not
/// a regular file, when group or others have any permission on it (mode & 077: a key others
/// can read is shared with them, one they can write they can replace), or when it holds
/// fewer than kMinAuthKeyBytes or more than kMaxAuthKeyBytes bytes.
AuthKey ReadAuthKeyFile(const std::string& path);

}  // namespace h4::bus

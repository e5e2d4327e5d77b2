// HMAC-SHA256 through OpenSSL's libcrypto; see hmac_sha256.h.
#include "messages/bus/hmac_sha256.h"

#include <stdexcept>

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

namespace h4::bus {

HmacSha256Digest HmacSha256(const std::vector<uint8_t>& key, const void* data, size_t size) {
  HmacSha256Digest digest{};
  unsigned int digest_size = 0;
  // HMAC() wants non-null pointers even for empty inputs.
  static const uint8_t kEmpty = 0;
  const uint8_t* key_bytes = key.empty() ? &kEmpty : key.data();
  const auto* bytes = size == 0 ? &kEmpty : static_cast<const uint8_t*>(data);
  if (HMAC(EVP_sha256(), key_bytes, static_cast<int>(key.size()), bytes, size, digest.data(),
           &digest_size) == nullptr ||
      digest_size != kHmacSha256Bytes) {
    throw std::runtime_error("OpenSSL HMAC-SHA256 failed");
  }
  return digest;
}

bool ConstantTimeEqual(const void* a, const void* b, size_t size) {
  return CRYPTO_memcmp(a, b, size) == 0;
}

void SecureRandomBytes(void* out, size_t size) {
  if (RAND_bytes(static_cast<unsigned char*>(out), static_cast<int>(size)) != 1) {
    throw std::runtime_error("OpenSSL RAND_bytes failed (no entropy source?)");
  }
}

}  // namespace h4::bus

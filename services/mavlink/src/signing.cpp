#include "cover/mavlink/signing.hpp"

#include <openssl/sha.h>

#include <algorithm>

namespace cover::mavlink {

namespace {
// 2015-01-01 00:00:00 UTC in Unix microseconds: the signing epoch.
constexpr std::int64_t kSigningEpochUnixUs = 1420070400LL * 1000000LL;
}  // namespace

std::uint64_t signing_timestamp(std::int64_t unix_us) {
  if (unix_us <= kSigningEpochUnixUs) return 0;
  return static_cast<std::uint64_t>((unix_us - kSigningEpochUnixUs) / 10);
}

// The low-level SHA256_* calls are deprecated in OpenSSL 3 in favour of EVP, but EVP
// allocates a context per digest; these work on a stack context, so the parser keeps its
// no-allocation promise on signed frames too.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
std::array<std::uint8_t, 6> signature_of(const SigningKey& key, const std::uint8_t* bytes,
                                         std::size_t signed_size, std::uint8_t link_id,
                                         std::uint64_t timestamp) {
  std::array<std::uint8_t, 7> tail{};
  tail[0] = link_id;
  for (std::size_t i = 0; i < 6; ++i) {
    tail[1 + i] = static_cast<std::uint8_t>(timestamp >> (8 * i));
  }
  SHA256_CTX context;
  SHA256_Init(&context);
  SHA256_Update(&context, key.secret.data(), key.secret.size());
  SHA256_Update(&context, bytes, signed_size);
  SHA256_Update(&context, tail.data(), tail.size());
  std::array<std::uint8_t, SHA256_DIGEST_LENGTH> digest{};
  SHA256_Final(digest.data(), &context);
  std::array<std::uint8_t, 6> signature{};
  std::copy_n(digest.begin(), signature.size(), signature.begin());
  return signature;
}
#pragma GCC diagnostic pop

}  // namespace cover::mavlink

#pragma once

#include <array>
#include <cstdint>

#include "cover/mavlink/frame.hpp"

namespace cover::mavlink {

// MAVLink v2 message signing: a 32-byte secret shared by the link's ends. The signature
// is link id (1) + timestamp (6, 10 us units since 2015-01-01 00:00:00 UTC) + the first 6
// bytes of SHA-256(key + header + payload + crc + link id + timestamp).
struct SigningKey {
  std::array<std::uint8_t, 32> secret{};
  std::uint8_t link_id = 0;
};

// 10-microsecond units since 2015-01-01 from a Unix time in microseconds.
std::uint64_t signing_timestamp(std::int64_t unix_us);

// The 6-byte signature of the frame `bytes[0, signed_size)` (header through checksum),
// with `link_id` and `timestamp`.
std::array<std::uint8_t, 6> signature_of(const SigningKey& key, const std::uint8_t* bytes,
                                         std::size_t signed_size, std::uint8_t link_id,
                                         std::uint64_t timestamp);

}  // namespace cover::mavlink

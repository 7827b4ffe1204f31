#pragma once

#include <cstddef>
#include <cstdint>

namespace cover::mcap {

// CRC-32 (IEEE 802.3, zlib's), as MCAP's chunk, data and summary checksums use.
// Incremental: crc32_update(crc32_update(0, a), b) == crc32 of a then b.
std::uint32_t crc32_update(std::uint32_t crc, const void* data, std::size_t size);

}  // namespace cover::mcap

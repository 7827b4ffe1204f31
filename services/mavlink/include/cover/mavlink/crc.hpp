#pragma once

#include <cstddef>
#include <cstdint>

namespace cover::mavlink {

// CRC-16/MCRF4XX (the X.25 checksum MAVLink uses): polynomial 0x1021 reflected, init
// 0xFFFF, no final xor.
inline constexpr std::uint16_t kCrcInit = 0xFFFF;
std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc);
std::uint16_t crc_accumulate(const std::uint8_t* data, std::size_t size, std::uint16_t crc);

}  // namespace cover::mavlink

#pragma once

#include <cstdint>
#include <cstring>

// Network byte order for the client's reads and writes (the server in sim/mocap has its
// own: a mistake in one must not hide in the other).
namespace cover::vrpn::detail {

inline std::uint32_t load_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | static_cast<std::uint32_t>(p[3]);
}
inline std::int32_t load_i32(const std::uint8_t* p) {
  return static_cast<std::int32_t>(load_u32(p));
}
inline double load_f64(const std::uint8_t* p) {
  const std::uint64_t bits = static_cast<std::uint64_t>(load_u32(p)) << 32 | load_u32(p + 4);
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
inline void store_u32(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 24);
  p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8);
  p[3] = static_cast<std::uint8_t>(v);
}
inline void store_i32(std::uint8_t* p, std::int32_t v) {
  store_u32(p, static_cast<std::uint32_t>(v));
}

}  // namespace cover::vrpn::detail

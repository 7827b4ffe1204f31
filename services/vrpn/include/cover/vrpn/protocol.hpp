#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

// The VRPN wire facts a tracker client needs, from the public VRPN sources
// (vrpn_Connection.C, vrpn_Tracker.C); docs/vrpn.md draws the layouts.
namespace cover::vrpn {

inline constexpr std::uint16_t kDefaultPort = 3883;

// The cookie each side sends first: "vrpn: ver. 07.38" (older servers: 07.35), two spaces, the log
// mode character '0'..'3', five NUL bytes.
inline constexpr std::string_view kMagic = "vrpn: ver. 07.38";
inline constexpr std::size_t kCookieBytes = 24;

// Six big-endian int32: length, seconds, microseconds, sender, type, sequence (unused).
inline constexpr std::size_t kHeaderBytes = 24;

// System message types (negative ids). For both descriptions the id described is in the
// header's sender field (vrpn_Connection.C, pack_type_description), not its type field.
inline constexpr std::int32_t kSenderDescription = -1;
inline constexpr std::int32_t kTypeDescription = -2;
inline constexpr std::int32_t kUdpDescription = -3;
inline constexpr std::int32_t kLogDescription = -4;
inline constexpr std::int32_t kDisconnectMessage = -5;

inline constexpr std::string_view kPosQuatType = "vrpn_Tracker Pos_Quat";
inline constexpr std::string_view kVelocityType = "vrpn_Tracker Velocity";
inline constexpr std::string_view kPingType = "vrpn_Base ping_message";
inline constexpr std::string_view kPongType = "vrpn_Base pong_message";

// Payloads: int32 sensor, int32 padding, then big-endian doubles. Pos_Quat: position (3),
// quaternion x, y, z, w (4). Velocity: velocity (3), velocity quaternion (4), its dt (1).
inline constexpr std::size_t kPosQuatBytes = 64;
inline constexpr std::size_t kVelocityBytes = 72;

// Payloads are padded with zeros to a multiple of 8; the header's length excludes it.
constexpr std::size_t ceil8(std::size_t n) {
  return (n + 7) / 8 * 8;
}

// A VRPN timestamp: the sender's clock (a struct timeval).
struct ServerTime {
  std::int32_t seconds = 0;
  std::int32_t microseconds = 0;
  std::int64_t to_ns() const {
    return static_cast<std::int64_t>(seconds) * 1'000'000'000 +
           static_cast<std::int64_t>(microseconds) * 1'000;
  }
};

enum class CookieCheck {
  Match,          // same version
  MinorMismatch,  // same major version: works, worth a warning
  Mismatch,       // not VRPN, or another major version: drop the connection
};

// The cookie this side sends (log mode 0: the server logs nothing for us).
std::array<std::uint8_t, kCookieBytes> make_cookie();
// Judges the peer's cookie: only the version up to its last '.' must match.
CookieCheck check_cookie(const std::uint8_t* cookie);

}  // namespace cover::vrpn

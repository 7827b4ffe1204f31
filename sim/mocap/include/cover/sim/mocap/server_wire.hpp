#pragma once

#include <cstdint>
#include <string>
#include <vector>

// The VRPN server's bytes (docs/vrpn.md), written apart from the client's encoder in
// services/vrpn so that a mistake in one side does not hide in the other; both are checked
// against hand-written bytes.
namespace cover::sim::mocap::wire {

inline constexpr std::size_t kCookieSize = 24;
inline constexpr std::size_t kHeaderSize = 24;
inline constexpr char kVersion[] = "vrpn: ver. 07.38";

// Our type ids on every connection.
enum ServerType : std::int32_t { kPosQuat = 0, kVelocity = 1, kPing = 2, kPong = 3 };
extern const char* const kTypeNames[4];

struct Stamp {
  std::int64_t seconds = 0;
  std::int64_t microseconds = 0;
};
Stamp stamp_of(std::int64_t time_ns);

void put_cookie(std::vector<std::uint8_t>& out);
// A message: header, payload, zero padding to 8; the length field leaves the padding out.
void put_message(std::vector<std::uint8_t>& out, std::int32_t sender, std::int32_t type,
                 Stamp stamp, const std::uint8_t* payload, std::size_t payload_size);
// Sender (-1) or type (-2) description: the described id goes in the sender field.
void put_description(std::vector<std::uint8_t>& out, std::int32_t system_type, std::int32_t id,
                     const std::string& name);
// vrpn_Tracker Pos_Quat, sensor 0: position, then quaternion x, y, z, w.
void put_pos_quat(std::vector<std::uint8_t>& out, std::int32_t sender, Stamp stamp,
                  const double position[3], const double quaternion_xyzw[4]);

}  // namespace cover::sim::mocap::wire

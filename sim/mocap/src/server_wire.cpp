#include "cover/sim/mocap/server_wire.hpp"

#include <endian.h>

#include <cstring>

namespace cover::sim::mocap::wire {
namespace {

void put_be32(std::vector<std::uint8_t>& out, std::int32_t value) {
  const std::uint32_t be = htobe32(static_cast<std::uint32_t>(value));
  const auto* p = reinterpret_cast<const std::uint8_t*>(&be);
  out.insert(out.end(), p, p + 4);
}

void put_be_double(std::uint8_t* at, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  const std::uint64_t be = htobe64(bits);
  std::memcpy(at, &be, sizeof be);
}

}  // namespace

const char* const kTypeNames[4] = {"vrpn_Tracker Pos_Quat", "vrpn_Tracker Velocity",
                                   "vrpn_Base ping_message", "vrpn_Base pong_message"};

Stamp stamp_of(std::int64_t time_ns) {
  std::int64_t seconds = time_ns / 1'000'000'000;
  std::int64_t rest_ns = time_ns % 1'000'000'000;
  if (rest_ns < 0) {
    seconds -= 1;
    rest_ns += 1'000'000'000;
  }
  return {seconds, rest_ns / 1000};
}

void put_cookie(std::vector<std::uint8_t>& out) {
  char cookie[kCookieSize] = {};
  std::memcpy(cookie, kVersion, 16);
  std::memcpy(cookie + 16, "  0", 3);
  out.insert(out.end(), cookie, cookie + kCookieSize);
}

void put_message(std::vector<std::uint8_t>& out, std::int32_t sender, std::int32_t type,
                 Stamp stamp, const std::uint8_t* payload, std::size_t payload_size) {
  put_be32(out, static_cast<std::int32_t>(kHeaderSize + payload_size));
  put_be32(out, static_cast<std::int32_t>(stamp.seconds));
  put_be32(out, static_cast<std::int32_t>(stamp.microseconds));
  put_be32(out, sender);
  put_be32(out, type);
  put_be32(out, 0);
  out.insert(out.end(), payload, payload + payload_size);
  const std::size_t padding = (8 - payload_size % 8) % 8;
  out.insert(out.end(), padding, 0);
}

void put_description(std::vector<std::uint8_t>& out, std::int32_t system_type, std::int32_t id,
                     const std::string& name) {
  std::vector<std::uint8_t> payload;
  put_be32(payload, static_cast<std::int32_t>(name.size() + 1));
  payload.insert(payload.end(), name.begin(), name.end());
  payload.push_back('\0');
  put_message(out, id, system_type, Stamp{}, payload.data(), payload.size());
}

void put_pos_quat(std::vector<std::uint8_t>& out, std::int32_t sender, Stamp stamp,
                  const double position[3], const double quaternion_xyzw[4]) {
  std::uint8_t payload[64] = {};  // sensor 0 and its padding copy: zeros
  for (int i = 0; i < 3; ++i) put_be_double(payload + 8 + 8 * i, position[i]);
  for (int i = 0; i < 4; ++i) put_be_double(payload + 32 + 8 * i, quaternion_xyzw[i]);
  put_message(out, sender, kPosQuat, stamp, payload, sizeof payload);
}

}  // namespace cover::sim::mocap::wire

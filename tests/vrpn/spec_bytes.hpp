#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

// Bytes written by hand from the VRPN protocol (docs/vrpn.md), for the client's and the
// server's tests: neither side's encoder is used to check the other. There is no VRPN
// implementation on npm or in Debian to run against.
namespace cover::test::vrpn_spec {

using Bytes = std::vector<std::uint8_t>;

inline Bytes hex(const std::string& text) {
  Bytes out;
  std::string digits;
  for (char c : text) {
    if (std::isxdigit(static_cast<unsigned char>(c))) digits += c;
  }
  for (std::size_t i = 0; i + 1 < digits.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
  }
  return out;
}

inline Bytes text(const std::string& s) {
  return Bytes(s.begin(), s.end());
}

inline Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// "vrpn: ver. 07.38", two spaces, log mode '0', five NULs.
inline Bytes cookie(const std::string& version = "07.38") {
  return cat({text("vrpn: ver. " + version + "  0"), hex("00 00 00 00 00")});
}

// Sender description of id 0, "UAV_A": length 24 + 4 + 6 = 34 (0x22), type -1, payload
// 00000006 "UAV_A\0" padded to 16.
inline Bytes sender_uav_a_id0() {
  return hex(
      "00000022 00000000 00000000 00000000 ffffffff 00000000"
      "00000006 5541565f 41 00 000000000000");
}

// Type description of id 5, "vrpn_Tracker Pos_Quat" (21 chars): length 24 + 4 + 22 = 50
// (0x32), the described id in the sender field, type -2; payload padded from 26 to 32.
inline Bytes type_pos_quat_id5() {
  return cat({hex("00000032 00000000 00000000 00000005 fffffffe 00000000 00000016"),
              text("vrpn_Tracker Pos_Quat"), hex("00 000000000000")});
}

// Pos_Quat of sender 0, type 5 at t = 1.5 s: sensor 0, position (1, 2, -0.5), quaternion
// x, y, z, w = (0, 0, 0.6, 0.8). Length 24 + 64 = 88 (0x58), no padding.
inline Bytes pos_quat_sender0_type5() {
  return hex(
      "00000058 00000001 0007a120 00000000 00000005 00000000"
      "00000000 00000000"
      "3ff0000000000000 4000000000000000 bfe0000000000000"
      "0000000000000000 0000000000000000 3fe3333333333333 3fe999999999999a");
}

}  // namespace cover::test::vrpn_spec

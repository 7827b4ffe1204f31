#pragma once

#include <array>
#include <cstdint>

#include "cover/vrpn/protocol.hpp"

namespace cover::vrpn {

// One tracker message of a body the session was asked for.
struct TrackerReport {
  enum class Kind : std::uint8_t { Pose, Velocity };
  int body = 0;  // index into SessionOptions::bodies
  std::int32_t sensor = 0;
  ServerTime time;  // the server's capture time, on the server's clock
  Kind kind = Kind::Pose;
  // false: the server sent NaN / infinite values, an absurd position or a zero quaternion
  // (an occluded body): the body is lost at `time`, the numbers below are zero.
  bool valid = false;
  std::array<double, 3> position{};  // Pose: m (server units); Velocity: per second
  // Pose: unit quaternion, x, y, z, w (normalised here); Velocity: the server's velocity
  // quaternion as sent.
  std::array<double, 4> quaternion_xyzw{0.0, 0.0, 0.0, 1.0};
};

}  // namespace cover::vrpn

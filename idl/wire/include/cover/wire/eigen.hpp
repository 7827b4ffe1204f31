#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "cover/msg/types.hpp"

namespace cover::wire {

msg::Vector3 to_msg(const Eigen::Vector3d& v);
Eigen::Vector3d to_eigen(const msg::Vector3& v);
// Hamilton, w first on both sides.
msg::Quaternion to_msg(const Eigen::Quaterniond& q);
Eigen::Quaterniond to_eigen(const msg::Quaternion& q);

// Stamps: seconds on a library's clock <-> nanoseconds on the wire, rounded to the nearest
// nanosecond (a truncation would make 0.01 s read 9999999 ns).
std::int64_t to_stamp_ns(double seconds);
double to_seconds(std::int64_t stamp_ns);

}  // namespace cover::wire

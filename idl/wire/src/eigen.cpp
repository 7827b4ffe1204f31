#include "cover/wire/eigen.hpp"

#include <cmath>
#include <limits>

#include "cover/vocabulary/stamp.hpp"

namespace cover::wire {

msg::Vector3 to_msg(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

Eigen::Vector3d to_eigen(const msg::Vector3& v) {
  return {v.x, v.y, v.z};
}

msg::Quaternion to_msg(const Eigen::Quaterniond& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

Eigen::Quaterniond to_eigen(const msg::Quaternion& q) {
  return {q.w, q.x, q.y, q.z};
}

std::int64_t to_stamp_ns(double seconds) {
  if (!std::isfinite(seconds)) return 0;
  // Beyond +-292 years llround's result is unspecified: saturate instead.
  constexpr double kLimit_s = 9.2e9;
  if (seconds >= kLimit_s) return std::numeric_limits<std::int64_t>::max();
  if (seconds <= -kLimit_s) return std::numeric_limits<std::int64_t>::min();
  return clock::s_to_ns(seconds);
}

double to_seconds(std::int64_t stamp_ns) {
  return clock::ns_to_s(stamp_ns);
}

}  // namespace cover::wire

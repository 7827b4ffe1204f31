#include "cover/wire/eigen.hpp"

#include <cmath>

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
  return std::isfinite(seconds) ? std::llround(seconds * 1e9) : 0;
}

double to_seconds(std::int64_t stamp_ns) {
  return static_cast<double>(stamp_ns) * 1e-9;
}

}  // namespace cover::wire

#include "cover/wire/intake.hpp"

#include <cmath>

#include "cover/wire/eigen.hpp"

namespace cover::wire {
namespace {

bool finite(const msg::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double norm(const msg::Vector3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

}  // namespace

const char* to_string(Rejection reason) {
  switch (reason) {
    case Rejection::NonFinite:
      return "non-finite";
    case Rejection::OutOfRange:
      return "out-of-range";
    case Rejection::UnknownId:
      return "unknown-id";
    case Rejection::Stale:
      return "stale";
    case Rejection::Future:
      return "future";
  }
  return "unknown";
}

IntakeLimits IntakeLimits::load(config::YamlReader& reader) {
  IntakeLimits limits;
  reader.optional("max_position_m", limits.max_position_m);
  reader.optional("max_speed_m_s", limits.max_speed_m_s);
  reader.optional("attitude_norm_tolerance", limits.attitude_norm_tolerance);
  reader.optional("max_specific_force_m_s2", limits.max_specific_force_m_s2);
  reader.optional("max_angular_velocity_rad_s", limits.max_angular_velocity_rad_s);
  reader.optional("max_angular_acceleration_rad_s2", limits.max_angular_acceleration_rad_s2);
  reader.optional("future_tolerance_s", limits.future_tolerance_s);
  reader.optional("log_period_s", limits.log_period_s);
  reader.reject_unknown_keys();
  limits.validate();
  return limits;
}

IntakeLimits IntakeLimits::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

IntakeLimits IntakeLimits::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "intake", false);
  return load(reader);
}

void IntakeLimits::validate() const {
  const std::string ctx = "intake";
  config::check(positive(max_position_m), ctx + ".max_position_m", "must be > 0");
  config::check(positive(max_speed_m_s), ctx + ".max_speed_m_s", "must be > 0");
  config::check(positive(attitude_norm_tolerance) && attitude_norm_tolerance < 0.5,
                ctx + ".attitude_norm_tolerance", "must be in (0, 0.5)");
  config::check(positive(max_specific_force_m_s2), ctx + ".max_specific_force_m_s2", "must be > 0");
  config::check(positive(max_angular_velocity_rad_s), ctx + ".max_angular_velocity_rad_s",
                "must be > 0");
  config::check(positive(max_angular_acceleration_rad_s2), ctx + ".max_angular_acceleration_rad_s2",
                "must be > 0");
  config::check(positive(future_tolerance_s) && future_tolerance_s <= 10.0,
                ctx + ".future_tolerance_s", "must be in (0, 10]");
  config::check(positive(log_period_s) && log_period_s <= 3600.0, ctx + ".log_period_s",
                "must be in (0, 3600]");
}

std::optional<Rejection> check_content(const msg::RelativeState& s, std::uint32_t uav_id,
                                       std::uint32_t ugv_id, const IntakeLimits& limits) {
  if (s.uav_id != uav_id || s.ugv_id != ugv_id) return Rejection::UnknownId;
  if (!s.valid) return std::nullopt;  // the fields of a lost state are not read
  const msg::Quaternion& q = s.attitude;
  if (!finite(s.position_m) || !finite(s.velocity_m_s) || !std::isfinite(q.w) ||
      !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) ||
      !std::isfinite(s.position_std_m)) {
    return Rejection::NonFinite;
  }
  const double q_norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (s.stamp_ns < 0 || norm(s.position_m) > limits.max_position_m ||
      norm(s.velocity_m_s) > limits.max_speed_m_s ||
      std::abs(q_norm - 1.0) > limits.attitude_norm_tolerance || s.position_std_m < 0.0) {
    return Rejection::OutOfRange;
  }
  return std::nullopt;
}

std::optional<Rejection> check_content(const msg::UgvImu& s, std::uint32_t ugv_id,
                                       const IntakeLimits& limits) {
  if (s.ugv_id != ugv_id) return Rejection::UnknownId;
  // The speed is not checked: a non-finite or unknown speed already reads as "no estimate".
  if (!finite(s.specific_force_m_s2) || !finite(s.angular_velocity_rad_s) ||
      !finite(s.angular_acceleration_rad_s2)) {
    return Rejection::NonFinite;
  }
  if (s.stamp_ns < 0 || norm(s.specific_force_m_s2) > limits.max_specific_force_m_s2 ||
      norm(s.angular_velocity_rad_s) > limits.max_angular_velocity_rad_s ||
      norm(s.angular_acceleration_rad_s2) > limits.max_angular_acceleration_rad_s2) {
    return Rejection::OutOfRange;
  }
  return std::nullopt;
}

std::optional<Rejection> check_stamp(std::int64_t stamp_ns, std::optional<double> now_s,
                                     std::optional<std::int64_t> last_accepted_ns,
                                     const IntakeLimits& limits) {
  if (now_s && std::isfinite(*now_s) && to_seconds(stamp_ns) > *now_s + limits.future_tolerance_s) {
    return Rejection::Future;
  }
  if (last_accepted_ns && stamp_ns < *last_accepted_ns) return Rejection::Stale;
  return std::nullopt;
}

std::uint64_t RejectionCounts::total() const {
  std::uint64_t sum = 0;
  for (const std::uint64_t n : counts_) sum += n;
  return sum;
}

std::string RejectionCounts::summary() const {
  std::string text;
  for (const Rejection reason : kRejections) {
    if (of(reason) == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::string(to_string(reason)) + " " + std::to_string(of(reason));
  }
  return text.empty() ? "none" : text;
}

bool RejectionCounts::log_due(Rejection reason, double now_s, double period_s) {
  const auto i = static_cast<std::size_t>(reason);
  if (ever_logged_[i] && now_s - logged_s_[i] < period_s) return false;
  ever_logged_[i] = true;
  logged_s_[i] = now_s;
  return true;
}

}  // namespace cover::wire

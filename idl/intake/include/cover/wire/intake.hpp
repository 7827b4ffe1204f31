#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/msg/types.hpp"

namespace cover::wire {

// Why an agent refused an input sample before it could reach a controller. One table
// (kRejections / to_string) names them in logs, status and tests.
enum class Rejection : std::uint8_t {
  NonFinite,   // a NaN or infinite number
  OutOfRange,  // finite but beyond what the vehicle can physically measure
  UnknownId,   // the sample names another vehicle than the topic it came on
  Stale,       // stamped before the last accepted sample (replayed or reordered)
  Future,      // stamped ahead of the receiver's clock by more than the tolerance
};
inline constexpr std::array<Rejection, 5> kRejections = {
    Rejection::NonFinite, Rejection::OutOfRange, Rejection::UnknownId, Rejection::Stale,
    Rejection::Future};
const char* to_string(Rejection reason);

// Bounds of a plausible sample (config/intake.yaml, section `intake`); far above anything
// a real flight produces, so only corrupt or hostile samples meet them.
struct IntakeLimits {
  double max_position_m = 1000.0;            // |relative position|
  double max_speed_m_s = 50.0;               // |relative velocity|
  double attitude_norm_tolerance = 0.1;      // | |q| - 1 |
  double max_specific_force_m_s2 = 160.0;    // |UGV specific force| (16 g)
  double max_angular_velocity_rad_s = 35.0;  // |UGV angular velocity| (2000 deg/s)
  double max_angular_acceleration_rad_s2 = 1000.0;
  double future_tolerance_s = 0.5;  // a stamp this far ahead of the receiver's clock is refused
  double log_period_s = 1.0;        // at most one log line per reason and period

  static IntakeLimits load(config::YamlReader& reader);
  static IntakeLimits load_file(const std::string& path);  // section `intake`, optional
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static IntakeLimits from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;  // throws ConfigError naming the key
};

// Content checks, needing no clock: finite, in range, addressed to (uav_id, ugv_id).
// A relative state marked invalid (the estimator lost the UGV) is not rejected here: it is
// a valid report of a missing input.
std::optional<Rejection> check_content(const msg::RelativeState& sample, std::uint32_t uav_id,
                                       std::uint32_t ugv_id, const IntakeLimits& limits);
std::optional<Rejection> check_content(const msg::UgvImu& sample, std::uint32_t ugv_id,
                                       const IntakeLimits& limits);

// Stamp checks against the receiver's clock `now_s` (nullopt: not known yet, only the
// order is checked) and the stamp of the last accepted sample (nullopt: none yet).
std::optional<Rejection> check_stamp(std::int64_t stamp_ns, std::optional<double> now_s,
                                     std::optional<std::int64_t> last_accepted_ns,
                                     const IntakeLimits& limits);

// One topic's intake after the content check: the newest sample (its stamp not checked
// yet) and the last one whose stamp passed, which is what the receiver uses. A refused
// sample leaves the accepted one in place, to age into the failsafe ladder's stale input.
template <typename T>
class SampleSlot {
 public:
  void offer(const T& sample) { fresh_ = sample; }
  // Checks the fresh sample's stamp: accepted, or the reason (it is dropped either way).
  std::optional<Rejection> settle(std::optional<double> now_s, const IntakeLimits& limits) {
    if (!fresh_) return std::nullopt;
    const auto last = accepted_ ? std::optional<std::int64_t>(accepted_->stamp_ns) : std::nullopt;
    const auto why = check_stamp(fresh_->stamp_ns, now_s, last, limits);
    if (!why) accepted_ = fresh_;
    fresh_.reset();
    return why;
  }
  const std::optional<T>& accepted() const { return accepted_; }
  // Stamp of the newest content-checked sample, ns; -1 when none.
  std::int64_t newest_stamp_ns() const {
    return fresh_ ? fresh_->stamp_ns : accepted_ ? accepted_->stamp_ns : -1;
  }

 private:
  std::optional<T> fresh_;
  std::optional<T> accepted_;
};

// Rejections by reason. Not thread-safe: one owner (guard it with the owner's mutex).
class RejectionCounts {
 public:
  void add(Rejection reason) { ++counts_[static_cast<std::size_t>(reason)]; }
  std::uint64_t of(Rejection reason) const { return counts_[static_cast<std::size_t>(reason)]; }
  std::uint64_t total() const;
  // "non-finite 3, future 1" (reasons with a count only); "none" when empty.
  std::string summary() const;
  // True at most once per `period_s` per reason (`now_s`: any monotonic clock): rejected
  // samples are logged, but a flood of them does not flood the log.
  bool log_due(Rejection reason, double now_s, double period_s);

 private:
  std::array<std::uint64_t, kRejections.size()> counts_{};
  std::array<double, kRejections.size()> logged_s_{};
  std::array<bool, kRejections.size()> ever_logged_{};
};

}  // namespace cover::wire

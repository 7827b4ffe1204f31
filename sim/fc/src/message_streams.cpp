#include "cover/sim/fc/message_streams.hpp"

#include <cmath>

#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::sim::fc {

namespace {

// Simulated time is a sum of control periods: grid points are matched within this.
constexpr double kTimeTolerance_s = 1e-9;

double period_of(double rate_hz) {
  return rate_hz > 0.0 ? 1.0 / rate_hz : 0.0;
}

// The first grid point of `period_s` at or after `t_s`.
double grid_at_or_after(double t_s, double period_s) {
  return std::ceil((t_s - kTimeTolerance_s) / period_s) * period_s;
}

}  // namespace

MessageStreams::MessageStreams(Autopilot profile, const StreamRates& r) {
  namespace mav = mavlink;
  const std::uint32_t estimator =
      profile == Autopilot::Px4 ? mav::EstimatorStatus::kId : mav::EkfStatusReport::kId;
  const std::pair<std::uint32_t, double> rates[] = {
      {mav::Heartbeat::kId, r.heartbeat_hz},
      {mav::SysStatus::kId, r.sys_status_hz},
      {stream_id::kAttitude, r.attitude_hz},
      {mav::AttitudeQuaternion::kId, r.attitude_quaternion_hz},
      {mav::AttitudeTarget::kId, r.attitude_target_hz},
      {mav::HighresImu::kId, r.highres_imu_hz},
      {mav::BatteryStatus::kId, r.battery_status_hz},
      {estimator, r.estimator_hz},
      {mav::ExtendedSysState::kId, r.extended_sys_state_hz},
      {mav::LocalPositionNed::kId, r.local_position_ned_hz},
  };
  for (const auto& [id, rate_hz] : rates) {
    streams_.push_back({id, period_of(rate_hz), period_of(rate_hz), 0.0});
  }
  // Real PX4 streams about 25 message types COVER's codec does not know; two of them.
  if (profile == Autopilot::Px4) {
    for (const std::uint32_t id : {stream_id::kVfrHud, stream_id::kAltitude}) {
      streams_.push_back({id, period_of(r.codec_unknown_hz), period_of(r.codec_unknown_hz), 0.0});
    }
  }
}

MessageStreams::Stream* MessageStreams::find(std::uint32_t id) {
  for (Stream& s : streams_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

const MessageStreams::Stream* MessageStreams::find(std::uint32_t id) const {
  for (const Stream& s : streams_) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

bool MessageStreams::has(std::uint32_t id) const {
  return find(id) != nullptr;
}

bool MessageStreams::set_interval(std::uint32_t id, double interval_us, double now_s) {
  Stream* s = find(id);
  if (s == nullptr || !std::isfinite(interval_us)) return false;
  if (interval_us > 0.0) {
    s->period_s = interval_us * 1e-6;
  } else if (interval_us == 0.0) {
    s->period_s = s->default_period_s;
  } else if (interval_us == -1.0) {
    s->period_s = 0.0;
  } else {
    return false;
  }
  if (s->period_s > 0.0) s->next_due_s = grid_at_or_after(now_s, s->period_s);
  return true;
}

bool MessageStreams::due(std::uint32_t id, double now_s) {
  Stream* s = find(id);
  if (s == nullptr || s->period_s <= 0.0 || now_s + kTimeTolerance_s < s->next_due_s) return false;
  // The next grid point after now (a stream that fell behind does not burst).
  s->next_due_s = (std::floor((now_s + kTimeTolerance_s) / s->period_s) + 1.0) * s->period_s;
  return true;
}

double MessageStreams::rate_hz(std::uint32_t id) const {
  const Stream* s = find(id);
  return s != nullptr && s->period_s > 0.0 ? 1.0 / s->period_s : 0.0;
}

}  // namespace cover::sim::fc

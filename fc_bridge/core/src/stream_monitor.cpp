#include "cover/fc_bridge/stream_monitor.hpp"

#include <algorithm>
#include <cstdio>

#include "cover/mavlink/event_messages.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"

namespace cover::fc_bridge {
namespace {

namespace mav = cover::mavlink;
// A stream is missing after this many of its periods without a frame, and never sooner
// than kMinSilence_s: a loaded autopilot or link delays a frame or two.
constexpr double kSilencePeriods = 5.0;
constexpr double kMinSilence_s = 1.5;

}  // namespace

StreamMonitor::StreamMonitor(std::vector<StreamRequest> plan, double reask_s) : reask_s_(reask_s) {
  tracks_.reserve(plan.size());
  for (const StreamRequest& request : plan) {
    Track track;
    track.state.request = request;
    tracks_.push_back(track);
  }
}

void StreamMonitor::restart(double now_s) {
  for (Track& track : tracks_) {
    const StreamRequest request = track.state.request;
    track = Track{};
    track.state.request = request;
    track.next_ask_s = now_s;
  }
  in_flight_ = -1;
}

std::optional<CommandSpec> StreamMonitor::next_request(double now_s) {
  if (in_flight_ >= 0) return std::nullopt;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Track& track = tracks_[i];
    const bool due = !track.state.asked || !view(track, now_s).arriving;
    if (!due || now_s < track.next_ask_s) continue;
    CommandSpec spec;
    spec.command = mav::mav_cmd::kSetMessageInterval;
    spec.param[0] = static_cast<float>(track.state.request.message_id);
    spec.param[1] = static_cast<float>(1e6 / track.state.request.rate_hz);  // us
    in_flight_ = static_cast<int>(i);
    track.next_ask_s = now_s + reask_s_;
    return spec;
  }
  return std::nullopt;
}

void StreamMonitor::on_result(CommandOutcome outcome, const std::string& message, double now_s) {
  if (in_flight_ < 0) return;
  Track& track = tracks_[static_cast<std::size_t>(in_flight_)];
  in_flight_ = -1;
  track.state.asked = true;
  track.asked_at_s = now_s;
  track.state.refusal = outcome == CommandOutcome::Accepted ? "" : message;
}

void StreamMonitor::on_frame(std::uint32_t message_id, double now_s) {
  for (Track& track : tracks_) {
    if (track.state.request.message_id != message_id) continue;
    track.last_frame_s = now_s;
    if (track.window_start_s < 0.0) {  // the first frame opens the window, uncounted
      track.window_start_s = now_s;
      return;
    }
    ++track.window_frames;
    roll_window(track, now_s);
    return;
  }
}

bool StreamMonitor::has(std::uint32_t message_id) const {
  return std::any_of(tracks_.begin(), tracks_.end(), [&](const Track& track) {
    return track.state.request.message_id == message_id;
  });
}

double StreamMonitor::allowed_silence_s(const Track& track) const {
  return std::max(kMinSilence_s, kSilencePeriods / track.state.request.rate_hz);
}

// The rate: the frames after the one that opened the window, over the time since it; the
// frame that closes a window opens the next (counted once: a 1 Hz stream reads 1 Hz).
void StreamMonitor::roll_window(Track& track, double now_s) {
  if (now_s - track.window_start_s < kWindow_s) return;
  track.state.measured_hz = track.window_frames / (now_s - track.window_start_s);
  track.window_start_s = now_s;
  track.window_frames = 0;
}

StreamState StreamMonitor::view(const Track& track, double now_s) const {
  StreamState state = track.state;
  state.arriving =
      track.last_frame_s >= 0.0 && now_s - track.last_frame_s <= allowed_silence_s(track);
  if (!state.arriving) state.measured_hz = 0.0;
  return state;
}

std::vector<StreamState> StreamMonitor::states(double now_s) const {
  std::vector<StreamState> out;
  out.reserve(tracks_.size());
  for (const Track& track : tracks_) out.push_back(view(track, now_s));
  return out;
}

std::string StreamMonitor::missing_summary(double now_s) const {
  std::string summary;
  for (const Track& track : tracks_) {
    if (track.state.request.optional || view(track, now_s).arriving || !track.state.asked) {
      continue;
    }
    // Not missing yet while its first frames may still be on the way.
    const double since_s = now_s - std::max(track.asked_at_s, track.last_frame_s);
    if (since_s <= allowed_silence_s(track)) continue;
    char line[160];
    std::snprintf(line, sizeof line, "%s (asked %.0f Hz%s%s, none for %.1f s)",
                  track.state.request.name, track.state.request.rate_hz,
                  track.state.refusal.empty() ? "" : ": ", track.state.refusal.c_str(), since_s);
    if (!summary.empty()) summary += ", ";
    summary += line;
  }
  return summary;
}

std::vector<StreamRequest> stream_plan(Autopilot kind, const StreamRates& rates) {
  std::vector<StreamRequest> plan;
  const auto add = [&plan](std::uint32_t id, const char* name, double rate_hz,
                           bool optional = false) {
    if (rate_hz > 0.0) plan.push_back({id, name, rate_hz, optional});
  };
  add(mav::HighresImu::kId, "HIGHRES_IMU", rates.highres_imu_hz);
  add(mav::ExtendedSysState::kId, "EXTENDED_SYS_STATE", rates.extended_sys_state_hz);
  add(mav::SysStatus::kId, "SYS_STATUS", rates.sys_status_hz);
  add(mav::BatteryStatus::kId, "BATTERY_STATUS", rates.battery_status_hz);
  if (kind == Autopilot::Px4) {
    add(mav::EstimatorStatus::kId, "ESTIMATOR_STATUS", rates.estimator_status_hz);
  } else {
    add(mav::EkfStatusReport::kId, "EKF_STATUS_REPORT", rates.estimator_status_hz);
  }
  add(mav::AttitudeTarget::kId, "ATTITUDE_TARGET", rates.attitude_target_hz);
  add(mav::LocalPositionNed::kId, "LOCAL_POSITION_NED", rates.local_position_ned_hz, true);
  return plan;
}

}  // namespace cover::fc_bridge

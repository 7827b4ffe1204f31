#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/fc_bridge/command_sender.hpp"

namespace cover::fc_bridge {

// A message stream the bridge needs from the autopilot, at the rate it asks for.
struct StreamRequest {
  std::uint32_t message_id = 0;
  const char* name = "";
  double rate_hz = 0.0;
  // Used when it comes, not missed when it does not (LOCAL_POSITION_NED: a vehicle without
  // a position estimate has none). Still asked for again every reask_s.
  bool optional = false;
};

// How one requested stream is doing.
struct StreamState {
  StreamRequest request;
  bool asked = false;        // a SET_MESSAGE_INTERVAL for it was answered (any way)
  std::string refusal;       // the autopilot's refusal, empty when accepted
  double measured_hz = 0.0;  // over the last measuring window, 0 before one ended
  bool arriving = false;     // frames came within the allowed silence
};

// Asks the autopilot for the streams the bridge reads and watches that they come.
// ArduCopter streams nothing but HEARTBEAT until asked; PX4 streams a set of its own at its
// own rates (HIGHRES_IMU 50 Hz on its onboard link). Both take MAV_CMD_SET_MESSAGE_INTERVAL
// per message and per link, and forget it when they reboot. One request is in flight at a
// time (a COMMAND_ACK names only the command): the caller sends what next_request() gives
// and reports its answer. A stream silent for `silence_periods` of its period (at least
// `min_silence_s`) is missing: it is asked for again every `reask_s` and named in
// missing_summary().
class StreamMonitor {
 public:
  StreamMonitor(std::vector<StreamRequest> plan, double reask_s);

  // The link was (re)learned: every stream is asked for again.
  void restart(double now_s);
  // The next SET_MESSAGE_INTERVAL to send now, if any; its answer goes to on_result.
  std::optional<CommandSpec> next_request(double now_s);
  void on_result(CommandOutcome outcome, const std::string& message, double now_s);
  void on_frame(std::uint32_t message_id, double now_s);

  // The streams in the plan's order, their measured rate and whether they arrive.
  std::vector<StreamState> states(double now_s) const;
  // "HIGHRES_IMU (asked 100 Hz, none for 2.1 s), ..." or empty when every stream arrives
  // (or was not asked yet, or is optional).
  std::string missing_summary(double now_s) const;
  bool has(std::uint32_t message_id) const;

 private:
  struct Track {
    StreamState state;
    double asked_at_s = -1.0;  // when its request was answered
    double next_ask_s = 0.0;
    double last_frame_s = -1.0;
    double window_start_s = -1.0;  // the measuring window of its rate
    std::uint32_t window_frames = 0;
  };
  static constexpr double kWindow_s = 2.0;
  double allowed_silence_s(const Track& track) const;
  StreamState view(const Track& track, double now_s) const;
  static void roll_window(Track& track, double now_s);

  std::vector<Track> tracks_;
  double reask_s_;
  int in_flight_ = -1;  // index of the track whose request awaits its answer
};

// What the bridge asks of each autopilot family; a rate of 0 leaves the stream as the
// autopilot sends it (not asked, not watched).
struct StreamRates {
  double highres_imu_hz = 100.0;
  double extended_sys_state_hz = 5.0;
  double sys_status_hz = 2.0;
  double battery_status_hz = 1.0;
  double estimator_status_hz = 1.0;
  double attitude_target_hz = 0.0;
  double local_position_ned_hz = 0.0;  // optional
};
std::vector<StreamRequest> stream_plan(Autopilot kind, const StreamRates& rates);

}  // namespace cover::fc_bridge

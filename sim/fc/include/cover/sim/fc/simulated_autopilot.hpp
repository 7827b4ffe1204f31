#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/battery_model.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim::fc {

// Something the autopilot did that a flight log shows (every one is also a STATUSTEXT).
struct AutopilotEvent {
  enum class Kind { Mode, Arming, Failsafe, Refusal, Payload };
  Kind kind = Kind::Mode;
  double time_s = 0.0;  // simulated
  std::string text;
};
const char* to_string(AutopilotEvent::Kind kind);

// What a received frame caused.
struct FrameResponse {
  std::vector<mavlink::EncodedFrame> frames;  // to send back at once (ACK, TIMESYNC, STATUSTEXT)
  bool setpoint_accepted = false;             // a SET_ATTITUDE_TARGET taken as the setpoint
  std::uint32_t setpoint_time_boot_ms = 0;    // its time_boot_ms
};

// What one control period of the autopilot produces.
struct AutopilotStep {
  std::vector<mavlink::EncodedFrame> frames;  // the streams due now, STATUSTEXT of events
  QuadrotorCommand plant_command;             // what the motors get (zero when disarmed)
  bool release_payload = false;               // a DO_GRIPPER release arrived since the last step
};

// One UAV's flight controller as a companion computer meets it over MAVLink, with PX4's or
// ArduPilot's rules (docs/autopilots.md), driven by the simulator's time:
//  - starts disarmed in MANUAL / STABILIZE; arms only on COMPONENT_ARM_DISARM (refused in
//    land mode, and in OFFBOARD / GUIDED_NOGPS without a fresh setpoint; param2 21196 forces);
//  - OFFBOARD / GUIDED_NOGPS only after setpoints streamed faster than
//    offboard_stream_min_rate_hz for offboard_stream_min_s (else COMMAND_ACK 1 temporarily
//    rejected (PX4) / 4 failed (ArduPilot), with a STATUSTEXT saying why);
//  - SET_ATTITUDE_TARGET: body rates (FRD) and normalised thrust, type_mask ignoring the
//    attitude, targeted at this system, from the first sender only; thrust u becomes
//    u * the vehicle's TRUE max thrust, so a bridge's wrong hover estimate matters;
//  - offboard loss: PX4 after COM_OF_LOSS_T lands (no GPS: descends); ArduPilot after
//    GUID_TIMEOUT levels and holds height, then lands after guid_level_hold_s;
//  - land mode: a levelled descent at land_speed_m_s, disarmed on touchdown;
//  - streams HEARTBEAT, ATTITUDE_QUATERNION, HIGHRES_IMU, ATTITUDE_TARGET,
//    EXTENDED_SYS_STATE, SYS_STATUS, BATTERY_STATUS at the configured rates.
// Not thread-safe: its owner serialises on_frame and step. Never throws after construction.
class SimulatedAutopilot {
 public:
  SimulatedAutopilot(AutopilotProfile profile, std::uint8_t system_id, const SimFcParams& params);

  // A frame from the link, received at simulated time `now_s`.
  FrameResponse on_frame(const mavlink::Frame& frame, double now_s);
  // The control period starting at `now_s` (the world as it is then).
  AutopilotStep step(double now_s, const World& world);

  // Fault injection: the safety pilot's RC mode switch (takes effect at once, whatever the
  // companion streams), and a flight controller whose heartbeats stop (the other streams go on).
  void inject_mode_switch(FlightMode mode);
  void stop_heartbeats();
  // The current HEARTBEAT, to repeat while simulated time stands still (lockstep waiting
  // for the companion); nullopt once heartbeats are stopped.
  std::optional<mavlink::EncodedFrame> heartbeat_frame();

  AutopilotProfile profile() const { return profile_; }
  std::uint8_t system_id() const { return encoder_.system_id(); }
  FlightMode mode() const { return mode_; }
  const char* mode_name() const { return fc::mode_name(profile_, mode_); }
  bool armed() const { return armed_; }
  bool heartbeats_stopped() const { return heartbeats_stopped_; }
  const std::vector<AutopilotEvent>& events() const { return events_; }
  std::uint64_t setpoints_accepted() const { return setpoints_accepted_; }
  std::uint64_t setpoints_ignored() const { return setpoints_ignored_; }

 private:
  struct Setpoint {
    mavlink::SetAttitudeTarget message;
    double received_s = 0.0;
  };
  struct Stream {
    double period_s = 1.0;
    double next_due_s = 0.0;
    bool due(double now_s);
  };

  // Frames and setpoints (simulated_autopilot.cpp).
  void handle_setpoint(const mavlink::Frame& frame, const mavlink::SetAttitudeTarget& setpoint,
                       double now_s, FrameResponse& response);
  bool setpoint_usable(const mavlink::Frame& frame, const mavlink::SetAttitudeTarget& setpoint,
                       double now_s);
  void handle_timesync(const mavlink::Timesync& request, double now_s);
  double setpoint_age_s(double now_s) const;
  bool stream_established(double now_s) const;
  bool setpoint_fresh(double now_s) const;
  void check_offboard_loss(double now_s);
  QuadrotorCommand plant_command(const World& world);
  QuadrotorCommand hold_command(const World& world);
  QuadrotorCommand setpoint_command(const World& world) const;

  // COMMAND_LONG (autopilot_commands.cpp).
  void handle_command(const mavlink::Frame& frame, const mavlink::CommandLong& command,
                      double now_s);
  std::uint8_t set_mode_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t arm_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t gripper_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t refused(const std::string& why, double now_s);
  std::uint8_t refusal_result() const;

  // State changes; each is an event and a STATUSTEXT.
  void set_mode(FlightMode mode, double now_s, const std::string& why);
  void arm(double now_s, const std::string& why);
  void disarm(double now_s, const std::string& why);
  void event(AutopilotEvent::Kind kind, double now_s, const std::string& text,
             std::uint8_t severity);
  // A warning about the companion's frames, at most once a second per text.
  void warn_limited(const std::string& text, double now_s);

  // Streams (autopilot_streams.cpp).
  void queue_streams(double now_s, const World& world, const QuadrotorCommand& command);
  mavlink::Heartbeat heartbeat() const;
  mavlink::HighresImu highres_imu(double now_s, const World& world) const;
  mavlink::AttitudeQuaternion attitude(double now_s, const World& world) const;
  mavlink::AttitudeTarget attitude_target(double now_s, const World& world,
                                          const QuadrotorCommand& command) const;
  std::uint8_t landed_state(const World& world) const;
  mavlink::SysStatus sys_status() const;
  mavlink::BatteryStatus battery_status() const;
  std::uint8_t system_status() const;

  template <typename Message>
  void queue(const Message& message) {
    outbox_.push_back(encoder_.encode(message));
  }

  AutopilotProfile profile_;
  SimFcParams params_;
  mavlink::Encoder encoder_;
  BatteryModel battery_;
  FlightMode mode_ = FlightMode::Manual;
  bool armed_ = false;
  bool resting_ = true;  // as of the last step: disarming in the air is refused
  bool in_failsafe_ = false;
  bool heartbeats_stopped_ = false;
  double last_now_s_ = 0.0;
  std::optional<double> last_step_s_;
  std::optional<double> hold_height_m_;  // captured on the first held step of a mode
  // ArduPilot: when GUID_TIMEOUT levelled the vehicle (nullopt: flying setpoints).
  std::optional<double> guided_levelled_since_s_;
  std::optional<Setpoint> setpoint_;
  double stream_start_s_ = 0.0;
  std::optional<std::pair<std::uint8_t, std::uint8_t>> companion_;  // system, component
  bool release_requested_ = false;
  std::uint64_t setpoints_accepted_ = 0;
  std::uint64_t setpoints_ignored_ = 0;
  Stream heartbeat_stream_, attitude_stream_, imu_stream_, target_stream_, ext_state_stream_,
      status_stream_;
  std::map<std::string, double> warned_at_s_;
  std::vector<AutopilotEvent> events_;
  std::vector<mavlink::EncodedFrame> outbox_;  // frames queued for the next response or step
};

}  // namespace cover::sim::fc

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
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/sim/fc/auto_disarm.hpp"
#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/autopilot_parameters.hpp"
#include "cover/sim/fc/battery_model.hpp"
#include "cover/sim/fc/message_streams.hpp"
#include "cover/sim/fc/px4_event.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim::fc {

// Something the autopilot did, for cover-sim's log and the run's result. What goes on the
// wire is the firmware's own report of it, if any: ArduPilot's STATUSTEXT, PX4's EVENT.
struct AutopilotEvent {
  enum class Kind { Mode, Arming, Failsafe, Refusal, Payload };
  Kind kind = Kind::Mode;
  double time_s = 0.0;  // simulated
  std::string text;
};
const char* to_string(AutopilotEvent::Kind kind);

// What a received frame caused.
struct FrameResponse {
  std::vector<mavlink::EncodedFrame> frames;  // to send back at once (ACK, PARAM_VALUE, ...)
  bool setpoint_accepted = false;             // a SET_ATTITUDE_TARGET taken as the setpoint
  std::uint32_t setpoint_time_boot_ms = 0;    // its time_boot_ms
};

// What one control period of the autopilot produces.
struct AutopilotStep {
  std::vector<mavlink::EncodedFrame> frames;  // the streams due now, reports of events
  QuadrotorCommand plant_command;             // what the motors get (zero when disarmed)
  bool release_payload = false;               // a DO_GRIPPER release arrived since the last step
};

// How a step's frames end. Real firmware has no such handshake; the simulator's lockstep
// does: in lockstep every step's frames end with a HIGHRES_IMU stamped with the step's time,
// whatever the HIGHRES_IMU stream's rate (even off), and a bridge takes it as the end of
// that step's frames (docs/flight-controller.md, "Lockstep"). Each step also carries a
// LOCAL_POSITION_NED, asked or not, so that the bridge's velocity-aided hover estimate does
// not depend on when its request arrived.
enum class StepClosing { None, HighresImu };

// One UAV's flight controller as a companion computer meets it over MAVLink, with the rules
// PX4 SITL and ArduCopter SITL showed COVER's bridge (docs/autopilots.md, "Our simulated
// autopilots and the real firmware"), driven by the simulator's time:
//  - boots in AUTO.LOITER (PX4) / STABILIZE (ArduPilot), disarmed;
//  - modes: OFFBOARD (PX4) is accepted while disarmed whatever the setpoints, while armed only
//    with an offboard signal (a setpoint within COM_OF_LOSS_T); GUIDED_NOGPS (ArduPilot) is
//    always accepted. PX4 answers every DO_SET_MODE with two identical COMMAND_ACKs;
//  - arming only on COMPONENT_ARM_DISARM: PX4 refuses it in OFFBOARD without an offboard
//    signal (1 TEMPORARILY_REJECTED), both in land mode; a disarm off the ground is refused
//    (PX4 1, ArduPilot 4 FAILED) unless forced (param2 21196);
//  - SET_ATTITUDE_TARGET: body rates (FRD) and normalised thrust, type_mask ignoring the
//    attitude, targeted at this system, from the first sender only; thrust u becomes
//    u * the vehicle's TRUE max thrust (ArduPilot with ATC_ANGLE_BOOST: / cos(tilt));
//  - offboard loss: PX4 after COM_OF_LOSS_T descends in land mode; ArduPilot after
//    GUID_TIMEOUT levels and holds height;
//  - ArduPilot's GCS failsafe (FS_GCS_ENABLE): armed, once a HEARTBEAT of MAV_GCS_SYSID (the
//    companion's) has come and then none for FS_GCS_TIMEOUT, LAND, its height held for 4 s
//    first (LAND_WITH_DELAY_MS), or a disarm on the ground;
//  - auto-disarm (AutoDisarm); land mode: a levelled descent at land_speed_m_s; after
//    PX4's disarm in it, its HEARTBEAT shows the mode before the landing again;
//  - streams (MessageStreams): PX4's onboard set, ArduPilot HEARTBEAT only, each changed by
//    SET_MESSAGE_INTERVAL; PARAM_REQUEST_READ answered (AutopilotParameters);
//  - reports: PX4 through EVENTs only, ArduPilot STATUSTEXT only once its link has received
//    a frame.
// Not thread-safe: its owner serialises on_frame and step. Never throws after construction.
class SimulatedAutopilot {
 public:
  SimulatedAutopilot(Autopilot profile, std::uint8_t system_id, const SimFcParams& params,
                     StepClosing closing = StepClosing::None);

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

  Autopilot profile() const { return profile_; }
  std::uint8_t system_id() const { return encoder_.system_id(); }
  FlightMode mode() const { return mode_; }
  const char* mode_name() const { return fc::mode_name(profile_, mode_); }
  bool armed() const { return armed_; }
  // Disarmed by the end of a landing in land mode (until armed again): PX4 shows its
  // previous mode again by then.
  bool landed_in_land_mode() const { return landed_in_land_mode_; }
  bool heartbeats_stopped() const { return heartbeats_stopped_; }
  const std::vector<AutopilotEvent>& events() const { return events_; }
  std::uint64_t setpoints_accepted() const { return setpoints_accepted_; }
  std::uint64_t setpoints_ignored() const { return setpoints_ignored_; }
  double stream_rate_hz(std::uint32_t message_id) const { return streams_.rate_hz(message_id); }
  // What its link was asked and answered (stream changes), for cover-sim's log, taken once.
  // Not events(): when a request arrives is the companion's timing, not the simulation's.
  std::vector<std::string> take_link_notes();

 private:
  struct Setpoint {
    mavlink::SetAttitudeTarget message;
    double received_s = 0.0;
  };

  // Frames and setpoints (simulated_autopilot.cpp).
  void handle_setpoint(const mavlink::Frame& frame, const mavlink::SetAttitudeTarget& setpoint,
                       double now_s, FrameResponse& response);
  bool setpoint_usable(const mavlink::Frame& frame, const mavlink::SetAttitudeTarget& setpoint,
                       double now_s);
  void handle_timesync(const mavlink::Timesync& request, double now_s);
  double setpoint_age_s(double now_s) const;
  bool offboard_signal(double now_s) const;
  void check_offboard_loss(double now_s);
  void check_gcs_failsafe(double now_s);
  void check_auto_disarm(double now_s);
  QuadrotorCommand plant_command(const World& world);
  QuadrotorCommand hold_command(const World& world);
  QuadrotorCommand setpoint_command(const World& world) const;

  // COMMAND_LONG (autopilot_commands.cpp).
  void handle_command(const mavlink::Frame& frame, const mavlink::CommandLong& command,
                      double now_s);
  std::uint8_t set_mode_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t arm_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t disarm_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t land_command(double now_s);
  std::uint8_t gripper_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t message_interval_command(const mavlink::CommandLong& command, double now_s);
  std::uint8_t refusal_result() const;

  // PARAM_REQUEST_READ (autopilot_commands.cpp).
  void handle_param_request(const mavlink::Frame& frame, const mavlink::ParamRequestRead& request);

  // State changes (autopilot_reports.cpp), each an event and the firmware's report of it.
  void set_mode(FlightMode mode, double now_s, const std::string& why);
  void arm(double now_s, const std::string& why);
  void disarm(double now_s, const std::string& why, std::uint8_t px4_reason);
  void log_event(AutopilotEvent::Kind kind, double now_s, const std::string& text);
  // ArduPilot's STATUSTEXT, sent only on a link that has received a frame (ArduPilot's
  // "active" channels); PX4 never sends one.
  void say(std::uint8_t severity, const std::string& text);
  // PX4's EVENT; ArduPilot never sends one.
  void report(const Px4Event& event, double now_s);
  // A warning about the companion's frames, at most once a second per text (log only: the
  // firmwares ignore such frames silently).
  void warn_limited(const std::string& text, double now_s);

  // Streams (autopilot_streams.cpp).
  void queue_streams(double now_s, const World& world, const QuadrotorCommand& command);
  void queue_unknown_types(double now_s, const World& world);
  void report_alignment(double now_s);
  bool estimator_aligned(double now_s) const;
  mavlink::Heartbeat heartbeat() const;
  mavlink::HighresImu highres_imu(double now_s, const World& world) const;
  mavlink::AttitudeQuaternion attitude(double now_s, const World& world) const;
  mavlink::EncodedFrame euler_attitude(double now_s, const World& world);
  mavlink::AttitudeTarget attitude_target(double now_s, const World& world,
                                          const QuadrotorCommand& command) const;
  std::uint8_t landed_state(const World& world) const;
  mavlink::SysStatus sys_status(double now_s) const;
  mavlink::BatteryStatus battery_status() const;
  mavlink::EncodedFrame estimator_report(double now_s);
  std::uint8_t system_status() const;

  template <typename Message>
  void queue(const Message& message) {
    outbox_.push_back(encoder_.encode(message));
  }

  Autopilot profile_;
  SimFcParams params_;
  StepClosing closing_;
  mavlink::Encoder encoder_;
  BatteryModel battery_;
  MessageStreams streams_;
  AutopilotParameters parameters_;
  AutoDisarm auto_disarm_;
  FlightMode mode_;
  FlightMode mode_before_land_;  // PX4 returns to it after disarming in land mode
  bool armed_ = false;
  bool landed_in_land_mode_ = false;
  bool resting_ = true;  // as of the last step: disarming in the air is refused
  bool in_failsafe_ = false;
  bool heartbeats_stopped_ = false;
  bool link_active_ = false;  // a frame has arrived (ArduPilot sends texts only then)
  bool alignment_reported_ = false;
  double last_now_s_ = 0.0;
  std::optional<double> last_step_s_;
  std::optional<double> hold_height_m_;  // captured on the first held step of a mode
  // ArduPilot: when GUID_TIMEOUT levelled the vehicle (nullopt: flying setpoints).
  std::optional<double> guided_levelled_since_s_;
  // ArduPilot's GCS failsafe: the watched HEARTBEAT's last arrival, whether the failsafe is
  // on, and until when a failsafe's LAND holds its height before descending.
  std::optional<double> gcs_seen_s_;
  bool gcs_failsafe_ = false;
  std::optional<double> land_descent_from_s_;
  std::optional<Setpoint> setpoint_;
  std::optional<std::pair<std::uint8_t, std::uint8_t>> companion_;  // system, component
  bool release_requested_ = false;
  std::uint16_t event_sequence_ = 0;  // PX4's EVENT sequence
  std::uint64_t setpoints_accepted_ = 0;
  std::uint64_t setpoints_ignored_ = 0;
  std::map<std::string, double> warned_at_s_;
  std::vector<AutopilotEvent> events_;
  std::vector<std::string> link_notes_;
  std::vector<mavlink::EncodedFrame> outbox_;  // frames queued for the next response or step
};

}  // namespace cover::sim::fc

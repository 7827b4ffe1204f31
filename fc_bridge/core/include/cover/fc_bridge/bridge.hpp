#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cover/fc_bridge/agent_command.hpp"
#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/fc_bridge/autopilot_session.hpp"
#include "cover/fc_bridge/command_gaps.hpp"
#include "cover/fc_bridge/command_sender.hpp"
#include "cover/fc_bridge/estimator_health.hpp"
#include "cover/fc_bridge/fc_bridge_params.hpp"
#include "cover/fc_bridge/hover_thrust_estimator.hpp"
#include "cover/fc_bridge/offboard_sequencer.hpp"
#include "cover/fc_bridge/parameter_check.hpp"
#include "cover/fc_bridge/safety_supervisor.hpp"
#include "cover/fc_bridge/setpoint_mapper.hpp"
#include "cover/fc_bridge/setpoint_stream.hpp"
#include "cover/fc_bridge/stream_monitor.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/frame.hpp"
#include "cover/mavlink/parser.hpp"

namespace cover::fc_bridge {

// An operator's command to the autopilot (cover/fc/request).
enum class OperatorCommand { Arm, Disarm, Offboard, Land };
const char* to_string(OperatorCommand command);

struct OperatorReply {
  std::string request_id;
  CommandOutcome outcome = CommandOutcome::NoAnswer;
  std::string message;
};

// A line for the log: every decision the bridge takes and every change it sees.
struct Notice {
  enum class Level { Info, Warning, Error };
  Level level = Level::Info;
  std::string text;
};

// The autopilot as the bridge sees it (cover/uav/U/fc without the DDS types).
struct FcStatus {
  bool link_ok = false;
  std::uint8_t reported_autopilot = 0;  // MAV_AUTOPILOT of its HEARTBEAT, 0: none yet
  std::uint8_t system_id = 0;
  bool armed = false;
  FcMode mode = FcMode::Unknown;
  std::string mode_name;
  std::uint32_t custom_mode = 0;
  LandedState landed_state = LandedState::Undefined;
  double battery_voltage_v = -1.0;
  double battery_remaining = -1.0;
  double hover_thrust = 0.0;
  double setpoint_rate_hz = 0.0;
  std::uint64_t rx_errors = 0;
  std::uint64_t rx_dropped = 0;
  std::uint64_t rx_unknown = 0;  // frames of message types the bridge does not read
  std::string status_text;       // the autopilot's last STATUSTEXT or (PX4) EVENT, in words
  bool offboard_ready = false;
  std::string failsafe;
  std::vector<StreamState> streams;  // the streams asked for, their measured rates
  std::string streams_missing;       // those that do not arrive, in words; empty: none
  EstimatorHealth estimator;
  std::vector<ParameterFinding> parameters;
  std::string flight_blocker;   // a parameter that makes COVER's flight wrong or unsafe
  double auto_disarm_s = -1.0;  // the autopilot disarms this long after arming on the ground
};

struct BridgeConfig {
  FcBridgeParams params;
  Autopilot autopilot = Autopilot::Px4;
  std::optional<mavlink::SigningKey> signing_key;  // signs what the bridge writes
};

// The flight-controller bridge's logic, apart from sockets, DDS and threads: frames from
// the autopilot and the agent's commands in, frames to write out, the time given by the
// caller (the simulator's in lockstep). Not thread-safe: the caller serialises the calls.
// Never throws after construction and never writes a NaN. The frame lists returned are
// valid until the next call.
class Bridge {
 public:
  explicit Bridge(const BridgeConfig& config);

  void on_frame(const mavlink::Frame& frame, double now_s);
  // The link's parser counts (rx errors, frames lost).
  void set_parser_stats(const mavlink::ParserStats& stats) { parser_stats_ = stats; }

  // The latency path: the SET_ATTITUDE_TARGET to write at once (and a land or gripper
  // command when the command asks for one). Nothing for a command that is not flyable
  // (NaN, absurd) or stale (a verbatim repeat of the last): it counts as missing.
  // Allocates nothing in the steady state.
  const std::vector<mavlink::EncodedFrame>& on_agent_command(const AgentCommand& command,
                                                             double now_s);
  // Whether the last on_agent_command wrote a setpoint (no autopilot heard yet, or a
  // command refused: it did not).
  bool setpoint_sent() const { return setpoint_sent_; }
  const std::vector<mavlink::EncodedFrame>& on_operator_request(OperatorCommand command,
                                                                const std::string& request_id,
                                                                double now_s);
  // Housekeeping (call at 50 Hz or more): the companion HEARTBEAT (1 Hz), command resends,
  // the failsafe and the automatic arming procedure.
  const std::vector<mavlink::EncodedFrame>& tick(double now_s);

  FcStatus state(double now_s) const;
  // The gaps between the agent's fresh commands since start (the command timeout's margin).
  const CommandGaps& command_gaps() const { return gaps_; }
  // Drained by the caller (it clears them).
  std::vector<Notice>& notices() { return notices_; }
  std::vector<OperatorReply>& replies() { return replies_; }

 private:
  enum class Origin { Operator, AutoOffboard, AutoArm, Failsafe, Gripper, StreamRequest };
  struct InFlight {
    std::uint64_t token = 0;
    Origin origin = Origin::Operator;
    std::string request_id;
    std::string what;  // "OFFBOARD", "arm"...
    CommandSpec spec;
  };

  double advance(double now_s);  // time never goes back inside the bridge
  AutopilotView view(double now_s) const;
  bool fresh(const AgentCommand& command);
  void note(Notice::Level level, std::string text);
  void note_session_changes(double now_s);
  void on_imu(const mavlink::Frame& frame, double now_s);
  void on_local_position(const mavlink::Frame& frame, double now_s);
  void on_attitude(const mavlink::Frame& frame);
  bool flying_our_thrust(double now_s) const;
  void note_estimate();
  void send_setpoint(const AgentCommand& command, double now_s);
  bool send_command(const CommandSpec& spec, Origin origin, std::string what,
                    const std::string& request_id, double now_s, bool preempt);
  void take_results(double now_s);
  void finish(const InFlight& flight, const CommandResult& result, double now_s);
  void supervise(double now_s, bool bridge_ran);
  void sequence(double now_s);
  void send_heartbeat(double now_s);
  void refuse(const std::string& request_id, std::string why);
  void learn_identity(double now_s);
  void on_event(const mavlink::Frame& frame);
  void on_parameter(const mavlink::Frame& frame, double now_s);
  void seed_hover_thrust();
  void request_streams(double now_s);
  void read_parameters(double now_s);
  void note_health_changes(double now_s);
  double auto_disarm_s() const;
  void hold_refusal(OperatorReply reply, double now_s);
  void release_refusals(double now_s);

  BridgeConfig config_;
  AutopilotProfile profile_;
  AutopilotSession session_;
  CommandSender sender_;
  SetpointMapper mapper_;
  SetpointStream stream_;
  HoverThrustEstimator estimator_;
  SafetySupervisor supervisor_;
  OffboardSequencer sequencer_;
  StreamMonitor streams_;
  ParameterCheck parameters_;
  EstimatorHealthTracker estimator_health_;
  mavlink::Encoder encoder_;
  mavlink::ParserStats parser_stats_;

  double now_s_ = -1e300;
  double last_tick_s_ = -1.0;
  bool event_seen_ = false;
  std::uint16_t last_event_sequence_ = 0;
  bool hover_seeded_ = false;
  CommandGaps gaps_;
  double last_fresh_s_ = -1.0;
  double next_heartbeat_s_ = 0.0;
  std::uint64_t next_token_ = 1;
  std::vector<InFlight> in_flight_;
  std::vector<mavlink::EncodedFrame> out_;
  std::vector<mavlink::CommandLong> resend_;
  std::vector<Notice> notices_;
  std::vector<OperatorReply> replies_;
  // The autopilot's recent texts, and refusals waiting a moment for their reason: PX4 says
  // why it refused (an EVENT) just before or after its COMMAND_ACK.
  struct RecentText {
    double at_s = 0.0;
    std::string text;
  };
  std::vector<RecentText> recent_texts_;
  struct HeldReply {
    OperatorReply reply;
    double since_s = 0.0;
    double release_s = 0.0;
  };
  std::vector<HeldReply> held_replies_;

  // The agent's stream.
  bool has_last_ = false;
  std::int64_t last_stamp_ns_ = 0;
  std::uint32_t last_seq_ = 0;
  bool last_sent_ = false;      // the last fresh command went out as a setpoint
  bool setpoint_sent_ = false;  // by the last on_agent_command
  bool rejecting_ = false;      // a run of unusable commands is logged once, at its start and end
  bool last_release_ = false;
  double last_thrust_ = 0.0;  // normalised, as last sent
  bool highres_imu_seen_ = false;

  // What was last logged, to log changes only.
  struct Seen {
    bool known = false;
    bool link_ok = false;
    bool armed = false;
    std::string mode_name;
    LandedState landed = LandedState::Undefined;
    std::uint64_t status_texts = 0;
    double hover_logged = 0.0;
    std::string streams_missing;
    std::string flight_blocker;
    std::string estimator;
  } seen_;
};

}  // namespace cover::fc_bridge

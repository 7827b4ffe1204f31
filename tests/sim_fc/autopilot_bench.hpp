#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "cover/fc_bridge/px4_events.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/event_messages.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/protocol.hpp"
#include "cover/mavlink/state_messages.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_params.hpp"

namespace cover::sim::fc::test {

// A world with the UAV on the ground at the origin (the default UGVs circle well away).
inline WorldParams ground_world() {
  WorldParams params = WorldParams::load_default();
  params.uav_initial.start_on_ugv = -1;
  params.uav_initial.position_m = Eigen::Vector3d::Zero();
  return params;
}

// A simulated autopilot on a world, and a companion talking to it with our codec: every
// frame either way goes through the Encoder and the StreamParser, as on the wire.
class AutopilotBench {
 public:
  static constexpr std::uint8_t kSystem = 3;  // not 1: the companion must target it
  static constexpr double kPeriodS = 0.01;

  explicit AutopilotBench(Autopilot profile, const WorldParams& world = ground_world(),
                          const SimFcParams& params = SimFcParams{},
                          StepClosing closing = StepClosing::None)
      : world_(world), autopilot_(profile, kSystem, params, closing) {}

  // Sends one message from the companion at the current time.
  template <typename Message>
  FrameResponse send(const Message& message, mavlink::Encoder* from = nullptr) {
    const mavlink::EncodedFrame encoded = (from ? *from : companion_).encode(message);
    std::optional<mavlink::Frame> frame;
    mavlink::StreamParser parser;
    parser.feed(encoded.bytes.data(), encoded.size, [&](const mavlink::Frame& f) { frame = f; });
    FrameResponse response = autopilot_.on_frame(*frame, t_s_);
    collect(response.frames);
    return response;
  }

  mavlink::SetAttitudeTarget setpoint(float thrust, float roll = 0.0F, float pitch = 0.0F,
                                      float yaw = 0.0F) const {
    mavlink::SetAttitudeTarget s;
    s.time_boot_ms = static_cast<std::uint32_t>(std::llround(t_s_ * 1000.0));
    s.body_roll_rate = roll;
    s.body_pitch_rate = pitch;
    s.body_yaw_rate = yaw;
    s.thrust = thrust;
    s.target_system = kSystem;
    s.target_component = 1;
    s.type_mask = mavlink::attitude_target_typemask::kIgnoreAttitude;
    return s;
  }

  // One control period: the autopilot steps, the world advances with its command.
  AutopilotStep tick() {
    AutopilotStep step = autopilot_.step(t_s_, world_);
    collect(step.frames);
    world_.advance(step.plant_command, kPeriodS);
    t_s_ = world_.state().time_s;
    return step;
  }

  // `duration_s` of control periods, a setpoint of `thrust` every other one (50 Hz).
  AutopilotStep stream(double duration_s, float thrust) {
    AutopilotStep last;
    const int ticks = static_cast<int>(std::lround(duration_s / kPeriodS));
    for (int i = 0; i < ticks; ++i) {
      if (i % 2 == 0) send(setpoint(thrust));
      last = tick();
    }
    return last;
  }

  // Ticks without setpoints.
  AutopilotStep idle(double duration_s) {
    AutopilotStep last;
    const int ticks = static_cast<int>(std::lround(duration_s / kPeriodS));
    for (int i = 0; i < ticks; ++i) last = tick();
    return last;
  }

  // Sends a COMMAND_LONG and returns its COMMAND_ACK (nullopt when none came back).
  std::optional<mavlink::CommandAck> command(std::uint16_t id, float p1 = 0, float p2 = 0,
                                             float p3 = 0) {
    mavlink::CommandLong c;
    c.command = id;
    c.param = {p1, p2, p3, 0, 0, 0, 0};
    c.target_system = kSystem;
    c.target_component = 1;
    const std::size_t before = received_.size();
    send(c);
    for (std::size_t i = before; i < received_.size(); ++i) {
      if (auto ack = mavlink::decode<mavlink::CommandAck>(received_[i])) return ack;
    }
    return std::nullopt;
  }
  std::optional<mavlink::CommandAck> set_mode(std::uint32_t main, std::uint32_t sub = 0) {
    return command(mavlink::mav_cmd::kDoSetMode, 1.0F, static_cast<float>(main),
                   static_cast<float>(sub));
  }
  std::optional<mavlink::CommandAck> arm(bool on = true, float p2 = 0.0F) {
    return command(mavlink::mav_cmd::kComponentArmDisarm, on ? 1.0F : 0.0F, p2);
  }
  // MAV_CMD_SET_MESSAGE_INTERVAL: `interval_us` > 0, 0 (default) or -1 (off).
  std::optional<mavlink::CommandAck> interval(std::uint32_t message_id, float interval_us) {
    return command(mavlink::mav_cmd::kSetMessageInterval, static_cast<float>(message_id),
                   interval_us);
  }
  // A HEARTBEAT from the companion (what makes an ArduPilot link "active").
  void companion_heartbeat() {
    mavlink::Heartbeat h;
    h.type = mavlink::mav_type::kOnboardController;
    h.autopilot = mavlink::mav_autopilot::kInvalid;
    send(h);
  }
  // PARAM_REQUEST_READ by name (index -1) or by index; the frames it answered with.
  std::vector<mavlink::Frame> read_parameter(const std::string& name, std::int16_t index = -1) {
    mavlink::ParamRequestRead request;
    request.param_index = index;
    request.target_system = kSystem;
    request.target_component = 1;
    request.param_id = mavlink::param_id_from(name);
    const std::size_t before = received_.size();
    send(request);
    return {received_.begin() + static_cast<std::ptrdiff_t>(before), received_.end()};
  }
  // The PX4 EVENTs sent so far, in the words of the bridge's decoder.
  std::vector<std::string> event_texts() const {
    std::vector<std::string> out;
    for (const auto& e : sent<mavlink::Event>())
      out.push_back(fc_bridge::describe_px4_event(e).text);
    return out;
  }
  // How many frames of message `id` the autopilot sent so far.
  std::size_t count(std::uint32_t id) const {
    std::size_t n = 0;
    for (const auto& f : received_) n += f.message_id == id ? 1 : 0;
    return n;
  }

  // Every frame of message M the autopilot sent so far.
  template <typename M>
  std::vector<M> sent() const {
    std::vector<M> out;
    for (const auto& f : received_) {
      if (auto m = mavlink::decode<M>(f)) out.push_back(*m);
    }
    return out;
  }
  std::string last_statustext() const {
    const auto texts = sent<mavlink::StatusText>();
    return texts.empty() ? "" : texts.back().text_string();
  }
  void clear() { received_.clear(); }

  SimulatedAutopilot& autopilot() { return autopilot_; }
  World& world() { return world_; }
  double t_s() const { return t_s_; }
  const std::vector<mavlink::Frame>& received() const { return received_; }
  const mavlink::ParserStats& parser_stats() const { return parser_.stats(); }

 private:
  void collect(const std::vector<mavlink::EncodedFrame>& frames) {
    for (const auto& e : frames) {
      parser_.feed(e.bytes.data(), e.size,
                   [&](const mavlink::Frame& f) { received_.push_back(f); });
    }
  }

  World world_;
  SimulatedAutopilot autopilot_;
  mavlink::Encoder companion_{245, mavlink::mav_comp::kOnboardComputer};
  mavlink::StreamParser parser_;
  std::vector<mavlink::Frame> received_;
  double t_s_ = 0.0;
};

}  // namespace cover::sim::fc::test

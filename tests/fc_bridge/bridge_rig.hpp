#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "cover/fc_bridge/bridge.hpp"
#include "cover/mavlink/parameter_messages.hpp"
#include "fake_autopilot.hpp"

namespace cover::fc_bridge::test {

namespace mav = cover::mavlink;

inline constexpr std::uint8_t kSys = 7;  // not 1: the bridge must learn it
inline constexpr double kStep_s = 0.01;  // the agent's 100 Hz

// A bridge and a hand-written autopilot, stepped at 100 Hz: the agent's command every
// step (while `agent_alive`), the bridge's tick every second step (50 Hz), the autopilot's
// HEARTBEAT at 1 Hz and landed state at 5 Hz. With `obey`, the autopilot acks every
// COMMAND_LONG as accepted and does what it asks.
struct BridgeRig {
  explicit BridgeRig(Autopilot kind = Autopilot::Px4, bool auto_arm = false)
      : BridgeRig(config(kind, auto_arm)) {}
  explicit BridgeRig(const BridgeConfig& config)
      : kind(config.autopilot),
        bridge(config),
        autopilot(kSys, AutopilotProfile(config.autopilot).mav_autopilot()) {
    custom_mode = kind == Autopilot::Px4 ? mav::px4_mode::custom_mode(mav::px4_mode::kMainPosctl)
                                         : mav::copter_mode::kStabilize;
  }
  static BridgeConfig config(Autopilot kind, bool auto_arm) {
    BridgeConfig c;
    c.autopilot = kind;
    c.params.auto_arm = auto_arm;
    return c;
  }
  std::uint32_t offboard_mode() const {
    return kind == Autopilot::Px4 ? mav::px4_mode::custom_mode(mav::px4_mode::kMainOffboard)
                                  : mav::copter_mode::kGuidedNoGps;
  }
  std::uint32_t land_mode() const {
    return kind == Autopilot::Px4
               ? mav::px4_mode::custom_mode(mav::px4_mode::kMainAuto, mav::px4_mode::kAutoSubLand)
               : mav::copter_mode::kLand;
  }
  std::uint32_t mode_of(const mav::CommandLong& c) const {
    const auto main = static_cast<std::uint8_t>(c.param[1]);
    const auto sub = static_cast<std::uint8_t>(c.param[2]);
    return kind == Autopilot::Px4 ? mav::px4_mode::custom_mode(main, sub) : main;
  }
  void heartbeat() { bridge.on_frame(autopilot.heartbeat(armed, custom_mode), t); }
  void flying() {  // armed in offboard, in the air
    armed = true;
    custom_mode = offboard_mode();
    landed = mav::mav_landed_state::kInAir;
    heartbeat();
    bridge.on_frame(autopilot.landed(landed), t);
  }
  AgentCommand command() {
    AgentCommand c;
    c.stamp_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    c.seq = ++seq;
    c.thrust_m_s2 = 9.81;
    c.armed = true;
    c.handover = handover;
    return c;
  }
  void take(const std::vector<mav::EncodedFrame>& frames) {
    written.insert(written.end(), frames.begin(), frames.end());
    if (obey) answer(frames);
  }
  void answer(const std::vector<mav::EncodedFrame>& frames) {
    for (const auto& request : decoded<mav::ParamRequestRead>(frames)) {
      const auto value = parameters.find(mav::param_id_string(request.param_id));
      if (value == parameters.end()) continue;  // an unknown name gets no answer
      mav::ParamValue answer;
      answer.param_id = request.param_id;
      answer.param_value = value->second;
      answer.param_index = 0xFFFF;
      bridge.on_frame(autopilot.send(answer), t);
    }
    for (const auto& c : commands(frames)) {
      if (c.command == mav::mav_cmd::kDoSetMode) custom_mode = mode_of(c);
      if (c.command == mav::mav_cmd::kNavLand) custom_mode = land_mode();
      if (c.command == mav::mav_cmd::kComponentArmDisarm) armed = c.param[0] > 0.5F;
      bridge.on_frame(autopilot.ack(c.command, mav::mav_result::kAccepted, 7, 191), t);
    }
  }
  void step() {
    t += kStep_s;
    ++steps;
    if (steps % 100 == 0 && heartbeats) heartbeat();
    if (steps % 20 == 0 && heartbeats) bridge.on_frame(autopilot.landed(landed), t);
    if (agent_alive) take(bridge.on_agent_command(command(), t));
    if (steps % 2 == 0) take(bridge.tick(t));
  }
  void run(double seconds) {
    const int n = static_cast<int>(std::lround(seconds / kStep_s));
    for (int i = 0; i < n; ++i) step();
  }
  std::vector<mav::CommandLong> sent_commands(std::uint16_t id) const {
    std::vector<mav::CommandLong> out;
    for (const auto& c : commands(written)) {
      if (c.command == id) out.push_back(c);
    }
    return out;
  }
  bool noticed(const std::string& text) const {
    for (const auto& n : bridge_notices) {
      if (n.text.find(text) != std::string::npos) return true;
    }
    return false;
  }
  void collect_notices() {
    auto& n = bridge.notices();
    bridge_notices.insert(bridge_notices.end(), n.begin(), n.end());
    n.clear();
  }

  Autopilot kind;
  Bridge bridge;
  FakeAutopilot autopilot;
  double t = 100.0;
  long steps = 0;
  std::uint32_t seq = 0;
  bool armed = false;
  std::uint32_t custom_mode = 0;
  std::uint8_t landed = mav::mav_landed_state::kOnGround;
  bool agent_alive = true;
  bool handover = false;
  bool heartbeats = true;
  bool obey = true;
  std::map<std::string, float> parameters;  // answered to PARAM_REQUEST_READ (with `obey`)
  std::vector<mav::EncodedFrame> written;
  std::vector<Notice> bridge_notices;
};

}  // namespace cover::fc_bridge::test

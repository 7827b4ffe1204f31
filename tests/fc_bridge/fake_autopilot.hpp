#pragma once

#include <cstdint>
#include <vector>

#include "cover/fc_bridge/bridge.hpp"
#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/mavlink/protocol.hpp"

namespace cover::fc_bridge::test {

// Frames as the wire carries them: encoded, then parsed back by our stream parser.
inline std::vector<mavlink::Frame> parse(const std::vector<mavlink::EncodedFrame>& encoded) {
  mavlink::StreamParser parser;
  std::vector<mavlink::Frame> frames;
  for (const auto& e : encoded) {
    parser.feed(e.bytes.data(), e.size, [&](const mavlink::Frame& f) { frames.push_back(f); });
  }
  return frames;
}

inline mavlink::Frame parse_one(const mavlink::EncodedFrame& encoded) {
  const auto frames = parse({encoded});
  return frames.empty() ? mavlink::Frame{} : frames.front();
}

template <typename M>
std::vector<M> decoded(const std::vector<mavlink::EncodedFrame>& encoded) {
  std::vector<M> out;
  for (const auto& f : parse(encoded)) {
    if (const auto m = mavlink::decode<M>(f)) out.push_back(*m);
  }
  return out;
}

inline std::vector<mavlink::CommandLong> commands(const std::vector<mavlink::EncodedFrame>& e) {
  return decoded<mavlink::CommandLong>(e);
}

// The autopilot's side, written by hand: the frames a PX4 or ArduPilot sends.
class FakeAutopilot {
 public:
  FakeAutopilot(std::uint8_t system_id, std::uint8_t mav_autopilot,
                std::uint8_t component_id = mavlink::mav_comp::kAutopilot1)
      : encoder_(system_id, component_id), mav_autopilot_(mav_autopilot) {}

  mavlink::Frame heartbeat(bool armed, std::uint32_t custom_mode) {
    mavlink::Heartbeat hb;
    hb.type = mavlink::mav_type::kQuadrotor;
    hb.autopilot = mav_autopilot_;
    hb.base_mode = mavlink::mav_mode_flag::kCustomModeEnabled |
                   (armed ? mavlink::mav_mode_flag::kSafetyArmed : 0);
    hb.custom_mode = custom_mode;
    hb.system_status = mavlink::mav_state::kActive;
    return parse_one(encoder_.encode(hb));
  }
  mavlink::Frame landed(std::uint8_t landed_state) {
    mavlink::ExtendedSysState e;
    e.landed_state = landed_state;
    return parse_one(encoder_.encode(e));
  }
  mavlink::Frame imu(float zacc_frd_m_s2) {
    mavlink::HighresImu imu;
    imu.zacc = zacc_frd_m_s2;
    return parse_one(encoder_.encode(imu));
  }
  mavlink::Frame ack(std::uint16_t command, std::uint8_t result, std::uint8_t target_system = 0,
                     std::uint8_t target_component = 0) {
    mavlink::CommandAck a;
    a.command = command;
    a.result = result;
    a.target_system = target_system;
    a.target_component = target_component;
    return parse_one(encoder_.encode(a));
  }
  // Any message, as this autopilot sends it.
  template <typename M>
  mavlink::Frame send(const M& message) {
    return parse_one(encoder_.encode(message));
  }
  mavlink::Frame status_text(const std::string& text, std::uint8_t severity) {
    mavlink::StatusText t;
    t.severity = severity;
    t.set_text(text);
    return parse_one(encoder_.encode(t));
  }

 private:
  mavlink::Encoder encoder_;
  std::uint8_t mav_autopilot_;
};

}  // namespace cover::fc_bridge::test

// cover-fc-bridge's reading of an autopilot: any bytes from its serial port or UDP socket,
// parsed and handed to the Bridge (HEARTBEAT, COMMAND_ACK, IMU, SYS_STATUS, PX4 EVENTs,
// PARAM_VALUEs, ESTIMATOR_STATUS / EKF_STATUS_REPORT...), with the bridge's own ticks and
// agent commands between them, as PX4 or as ArduPilot.
// Contract: no crash; the state the bridge reports stays sane whatever the autopilot says:
// the hover-thrust estimate finite and within its bounds, texts bounded, every parameter
// value finite or marked unknown, stream rates finite and >= 0, and no frame the bridge
// writes carries a non-finite number.
#include <cmath>
#include <cstdint>
#include <vector>

#include "cover/fc_bridge/bridge.hpp"
#include "cover/mavlink/messages.hpp"
#include "cover/mavlink/parser.hpp"
#include "fuzz_input.hpp"

namespace {

namespace fc = cover::fc_bridge;
namespace mav = cover::mavlink;
using cover::fuzz::require;

void check_written(const std::vector<mav::EncodedFrame>& frames) {
  mav::StreamParser parser;
  for (const auto& e : frames) {
    parser.feed(e.bytes.data(), e.size, [](const mav::Frame& f) {
      if (const auto s = mav::decode<mav::SetAttitudeTarget>(f)) {
        require(std::isfinite(s->thrust) && s->thrust >= 0.0F && s->thrust <= 1.0F,
                "setpoint thrust finite in [0, 1]");
        require(std::isfinite(s->body_roll_rate) && std::isfinite(s->body_pitch_rate) &&
                    std::isfinite(s->body_yaw_rate),
                "setpoint rates finite");
      }
      if (const auto c = mav::decode<mav::CommandLong>(f)) {
        for (const float p : c->param) require(std::isfinite(p), "command parameters finite");
      }
    });
  }
}

void check_state(const fc::FcStatus& s, const fc::FcBridgeParams& p) {
  require(std::isfinite(s.hover_thrust) && s.hover_thrust >= p.hover_thrust_min &&
              s.hover_thrust <= p.hover_thrust_max,
          "hover estimate finite within its bounds");
  require(s.status_text.size() <= 512, "status text bounded");
  require(s.streams_missing.size() <= 4096, "missing streams text bounded");
  for (const auto& f : s.parameters) {
    require(!f.known || std::isfinite(f.value), "a known parameter is a finite number");
  }
  for (const auto& stream : s.streams) {
    require(std::isfinite(stream.measured_hz) && stream.measured_hz >= 0.0, "stream rate sane");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  fc::BridgeConfig config;
  config.autopilot = (data[0] & 1) != 0 ? cover::Autopilot::ArduPilot : cover::Autopilot::Px4;
  config.params.hover_thrust_from_autopilot = (data[0] & 2) != 0;
  fc::Bridge bridge(config);
  mav::StreamParser parser;
  double now_s = 1.0;
  std::uint32_t seq = 0;
  // The bytes in chunks of 24 (a 100 Hz HIGHRES_IMU's share of 921600 baud is ~8 frames of
  // it per tick), each followed by a tick, an agent command and 7 ms.
  constexpr std::size_t kChunk = 24;
  for (std::size_t at = 1; at < size;) {
    const std::size_t n = std::min(kChunk, size - at);
    parser.feed(data + at, n, [&](const mav::Frame& f) {
      bridge.set_parser_stats(parser.stats());
      bridge.on_frame(f, now_s);
    });
    at += n;
    check_written(bridge.tick(now_s));
    fc::AgentCommand command;
    command.stamp_ns = static_cast<std::int64_t>(now_s * 1e9);
    command.seq = ++seq;
    command.thrust_m_s2 = 9.81;
    command.armed = true;
    check_written(bridge.on_agent_command(command, now_s));
    bridge.notices().clear();
    bridge.replies().clear();
    check_state(bridge.state(now_s), config.params);
    now_s += 0.007;
  }
  return 0;
}

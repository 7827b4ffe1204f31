#pragma once

#include <cstdint>
#include <vector>

#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

// Message ids the simulated autopilots stream that COVER's codec has no struct for.
namespace stream_id {
inline constexpr std::uint32_t kAttitude = 30;   // ATTITUDE (the codec knows its checksum)
inline constexpr std::uint32_t kVfrHud = 74;     // unknown to the codec
inline constexpr std::uint32_t kAltitude = 141;  // unknown to the codec
}  // namespace stream_id

// One autopilot link's message streams, each on its own interval, changed per message by
// MAV_CMD_SET_MESSAGE_INTERVAL as PX4 and ArduPilot change them (both measured): param2
// > 0 is the interval in microseconds, 0 the autopilot's default rate, -1 stops the stream.
// A stream is due on the grid of its interval in simulated time (k * interval): when a
// change arrives (a wall-clock accident, even in lockstep) moves no frame that both rates
// would send, and t = 0 is on every grid.
class MessageStreams {
 public:
  MessageStreams(Autopilot profile, const StreamRates& defaults);

  // Whether message `id` is one of this autopilot's streams (else a SET_MESSAGE_INTERVAL for
  // it is refused).
  bool has(std::uint32_t id) const;
  // Applies SET_MESSAGE_INTERVAL(id, interval_us) arriving at `now_s`; false when `id` is not
  // a stream or the interval is none of > 0, 0, -1.
  bool set_interval(std::uint32_t id, double interval_us, double now_s);
  // Whether message `id` is due in the step at `now_s` (then not again before its next grid
  // point). At most once per call time.
  bool due(std::uint32_t id, double now_s);
  double rate_hz(std::uint32_t id) const;  // 0: off

 private:
  struct Stream {
    std::uint32_t id = 0;
    double default_period_s = 0.0;  // 0: off by default
    double period_s = 0.0;          // 0: off
    double next_due_s = 0.0;
  };
  Stream* find(std::uint32_t id);
  const Stream* find(std::uint32_t id) const;

  std::vector<Stream> streams_;
};

}  // namespace cover::sim::fc

#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::sim_clock {

// Where the agent's time comes from:
//  lockstep: the simulator's ticks (cover/sim/clock): one control step per tick;
//  realtime: the simulator's time, extrapolated between its ticks with the host's clock;
//  system:   the host's clock (the field: stamps are system time on every vehicle).
enum class ClockMode { Lockstep, Realtime, System };
std::optional<ClockMode> parse_clock_mode(const std::string& text);

// A lockstep tick as the agent takes it. The simulator publishes a tick again until
// every agent has answered it, naming the UAVs whose answers it misses: an agent meets
// the tick it just answered again when its answer was lost (written before its command
// writer matched the simulator's reader): it then answers again, without stepping twice.
// A tick published again for other UAVs is not given to it at all (its answer arrived:
// writing it again would only add to what the simulator must read).
struct LockstepTick {
  msg::SimClock tick;
  bool answered_before = false;
};

class AgentClock {
 public:
  // `uav_id`: the UAV whose agent this is, -1: none (every tick published again is taken).
  AgentClock(dds::Participant& participant, ClockMode mode, int uav_id = -1);

  ClockMode mode() const { return mode_; }
  // Lockstep: the next tick to act on (a new one, or the last one published again),
  // waiting up to `timeout`.
  std::optional<LockstepTick> next_tick(std::chrono::milliseconds timeout);
  // Now on the clock the measurements are stamped with, s; nullopt before the simulator's
  // first tick (realtime) .
  std::optional<double> now_s() const;
  // Ticks published again for other UAVs only, not taken.
  std::uint64_t not_awaited() const;

 private:
  void on_tick(const msg::SimClock& tick);
  void queue_lockstep(const msg::SimClock& tick);  // mutex_ held
  // A tick published again that names other UAVs' answers as missing, not this one's.
  bool awaits_others(const msg::SimClock& tick) const;

  ClockMode mode_;
  int uav_id_;
  std::uint64_t not_awaited_ = 0;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<LockstepTick> ticks_;
  std::optional<msg::SimClock> last_tick_;
  std::int64_t last_tick_monotonic_ns_ = 0;
  std::optional<std::int64_t> clock_back_logged_ns_;  // the last "clock went back" line
  dds::Reader<msg::SimClock> reader_;                 // last: its callback uses the members above
};

}  // namespace cover::sim_clock

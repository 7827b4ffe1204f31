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

namespace cover::uav_agent {

// Where the agent's time comes from:
//  lockstep: the simulator's ticks (cover/sim/clock): one control step per tick;
//  realtime: the simulator's time, extrapolated between its ticks with the host's clock;
//  system:   the host's clock (the field: stamps are system time on every vehicle).
enum class ClockMode { Lockstep, Realtime, System };
std::optional<ClockMode> parse_clock_mode(const std::string& text);

class AgentClock {
 public:
  AgentClock(dds::Participant& participant, ClockMode mode);

  ClockMode mode() const { return mode_; }
  // Lockstep: the next tick not yet taken, waiting up to `timeout`.
  std::optional<msg::SimClock> next_tick(std::chrono::milliseconds timeout);
  // Now on the clock the measurements are stamped with, s; nullopt before the simulator's
  // first tick (realtime) .
  std::optional<double> now_s() const;

 private:
  void on_tick(const msg::SimClock& tick);

  ClockMode mode_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<msg::SimClock> ticks_;
  std::optional<msg::SimClock> last_tick_;
  std::int64_t last_tick_monotonic_ns_ = 0;
  dds::Reader<msg::SimClock> reader_;  // last: its callback uses the members above
};

}  // namespace cover::uav_agent

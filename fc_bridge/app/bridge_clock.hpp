#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>

#include "cover/dds/participant.hpp"
#include "cover/sim_clock/agent_clock.hpp"

namespace cover::fc_bridge {

// The bridge's time, on the clock the agent stamps its commands with:
//  lockstep: the simulator's newest tick, not extrapolated (while the simulator waits for a
//            slow agent its time stands still, and so do the bridge's timeouts);
//  realtime: the simulator's time, extrapolated between its ticks;
//  system:   the host's clock (the field).
class BridgeClock {
 public:
  // `zero_before_first_tick`: the simulator's time is 0 until its first tick instead of
  // unknown (a real firmware boots and aligns before the world's first tick, and the
  // simulator waits for the bridge to report it).
  BridgeClock(dds::Participant& participant, sim_clock::ClockMode mode,
              bool zero_before_first_tick = false);

  // Waits up to `timeout` (lockstep: for ticks, taking every one that arrived) or for a
  // shutdown request.
  void wait(std::chrono::milliseconds timeout);
  // nullopt before the simulator's first tick (lockstep, realtime), unless
  // zero_before_first_tick. Thread-safe.
  std::optional<double> now_s() const;
  // Lockstep: the agent answers only ticks the simulator has published, so a command's
  // stamp is a tick too, perhaps one this bridge's tick reader has not delivered yet. Time
  // taken from ticks alone would then lag the commands: a housekeeping thread starved for a
  // few wall-clock milliseconds saw 12 ticks at once, called the agent 120 ms silent and
  // landed a healthy flight. No-op on the other clocks.
  void observe_command_stamp(std::int64_t stamp_ns);

 private:
  void advance_to(std::int64_t stamp_ns);  // never backwards; from any thread

  sim_clock::ClockMode mode_;
  bool zero_before_first_tick_;
  sim_clock::AgentClock clock_;
  std::atomic<std::int64_t> tick_ns_{-1};
};

}  // namespace cover::fc_bridge

#include "bridge_clock.hpp"

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::fc_bridge {

BridgeClock::BridgeClock(dds::Participant& participant, sim_clock::ClockMode mode,
                         bool zero_before_first_tick)
    : mode_(mode), zero_before_first_tick_(zero_before_first_tick), clock_(participant, mode) {}

void BridgeClock::wait(std::chrono::milliseconds timeout) {
  if (mode_ != sim_clock::ClockMode::Lockstep) {
    process::ShutdownSignal::wait_for(timeout);
    return;
  }
  auto tick = clock_.next_tick(timeout);
  while (tick) {
    advance_to(tick->tick.stamp_ns);
    tick = clock_.next_tick(std::chrono::milliseconds(0));
  }
}

void BridgeClock::observe_command_stamp(std::int64_t stamp_ns) {
  if (mode_ == sim_clock::ClockMode::Lockstep) advance_to(stamp_ns);
}

void BridgeClock::advance_to(std::int64_t stamp_ns) {
  std::int64_t seen = tick_ns_.load();
  while (stamp_ns > seen && !tick_ns_.compare_exchange_weak(seen, stamp_ns)) {
  }
}

std::optional<double> BridgeClock::now_s() const {
  std::optional<double> now;
  if (mode_ != sim_clock::ClockMode::Lockstep) {
    now = clock_.now_s();
  } else if (const std::int64_t ns = tick_ns_.load(); ns >= 0) {
    now = clock::ns_to_s(ns);
  }
  if (!now && zero_before_first_tick_ && mode_ != sim_clock::ClockMode::System) return 0.0;
  return now;
}

}  // namespace cover::fc_bridge

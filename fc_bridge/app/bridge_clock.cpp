#include "bridge_clock.hpp"

#include "cover/clock/clock.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::fc_bridge {

BridgeClock::BridgeClock(dds::Participant& participant, sim_clock::ClockMode mode)
    : mode_(mode), clock_(participant, mode) {}

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
  if (mode_ != sim_clock::ClockMode::Lockstep) return clock_.now_s();
  const std::int64_t ns = tick_ns_.load();
  if (ns < 0) return std::nullopt;
  return clock::ns_to_s(ns);
}

}  // namespace cover::fc_bridge

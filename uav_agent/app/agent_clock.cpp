#include "agent_clock.hpp"

#include "cover/clock/clock.hpp"
#include "cover/wire/eigen.hpp"

namespace cover::uav_agent {

std::optional<ClockMode> parse_clock_mode(const std::string& text) {
  if (text == "lockstep") return ClockMode::Lockstep;
  if (text == "realtime") return ClockMode::Realtime;
  if (text == "system") return ClockMode::System;
  return std::nullopt;
}

AgentClock::AgentClock(dds::Participant& participant, ClockMode mode) : mode_(mode) {
  if (mode_ == ClockMode::System) return;
  reader_ = participant.make_reader(dds::topics::sim_clock(),
                                    [this](const msg::SimClock& tick) { on_tick(tick); });
}

void AgentClock::on_tick(const msg::SimClock& tick) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // The simulator repeats a tick until it is answered: take each one once.
    const bool repeated = last_tick_ && tick.tick <= last_tick_->tick;
    if (mode_ == ClockMode::Lockstep && !repeated) ticks_.push_back(tick);
    last_tick_ = tick;
    last_tick_monotonic_ns_ = clock::monotonic_ns();
  }
  arrived_.notify_all();
}

std::optional<msg::SimClock> AgentClock::next_tick(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!arrived_.wait_for(lock, timeout, [this] { return !ticks_.empty(); })) return std::nullopt;
  msg::SimClock tick = ticks_.front();
  ticks_.pop_front();
  return tick;
}

std::optional<double> AgentClock::now_s() const {
  if (mode_ == ClockMode::System) return wire::to_seconds(clock::system_ns());
  std::lock_guard<std::mutex> lock(mutex_);
  if (!last_tick_) return std::nullopt;
  const std::int64_t since_ns = clock::monotonic_ns() - last_tick_monotonic_ns_;
  return wire::to_seconds(last_tick_->stamp_ns + since_ns);
}

}  // namespace cover::uav_agent

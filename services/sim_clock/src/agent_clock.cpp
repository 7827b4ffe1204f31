#include "cover/sim_clock/agent_clock.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "cover/clock/clock.hpp"

namespace cover::sim_clock {

namespace {
constexpr std::int64_t kClockBackLogPeriodNs = 1'000'000'000;
}  // namespace

std::optional<ClockMode> parse_clock_mode(const std::string& text) {
  if (text == "lockstep") return ClockMode::Lockstep;
  if (text == "realtime") return ClockMode::Realtime;
  if (text == "system") return ClockMode::System;
  return std::nullopt;
}

AgentClock::AgentClock(dds::Participant& participant, ClockMode mode, int uav_id)
    : mode_(mode), uav_id_(uav_id) {
  if (mode_ == ClockMode::System) return;
  reader_ = participant.make_reader(dds::topics::sim_clock(),
                                    [this](const msg::SimClock& tick) { on_tick(tick); });
}

void AgentClock::on_tick(const msg::SimClock& tick) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (mode_ == ClockMode::Lockstep) queue_lockstep(tick);
    last_tick_ = tick;
    last_tick_monotonic_ns_ = clock::monotonic_ns();
  }
  arrived_.notify_all();
}

bool AgentClock::awaits_others(const msg::SimClock& tick) const {
  if (uav_id_ < 0 || tick.awaited.empty()) return false;
  return std::find(tick.awaited.begin(), tick.awaited.end(), static_cast<std::uint32_t>(uav_id_)) ==
         tick.awaited.end();
}

void AgentClock::queue_lockstep(const msg::SimClock& tick) {
  if (last_tick_ && tick.tick < last_tick_->tick) {
    // Time going back is a simulator started again on this domain (or a second one on
    // it): follow it; the intake then refuses samples older than the ones taken, and the
    // failsafe ladder acts on the stale inputs.
    const std::int64_t now_ns = clock::monotonic_ns();
    if (!clock_back_logged_ns_ || now_ns - *clock_back_logged_ns_ >= kClockBackLogPeriodNs) {
      spdlog::warn(
          "simulator clock went back from tick {} to tick {}: a new simulator run, or two on "
          "this domain",
          last_tick_->tick, tick.tick);
      clock_back_logged_ns_ = now_ns;
    }
  }
  const bool again = last_tick_ && tick.tick == last_tick_->tick;
  if (again && awaits_others(tick)) {
    ++not_awaited_;
    return;
  }
  // A tick already waiting to be answered needs no second entry.
  if (again && !ticks_.empty() && ticks_.back().tick.tick == tick.tick) return;
  ticks_.push_back({tick, again});
}

std::optional<LockstepTick> AgentClock::next_tick(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!arrived_.wait_for(lock, timeout, [this] { return !ticks_.empty(); })) return std::nullopt;
  LockstepTick tick = ticks_.front();
  ticks_.pop_front();
  return tick;
}

std::uint64_t AgentClock::not_awaited() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return not_awaited_;
}

std::optional<double> AgentClock::now_s() const {
  if (mode_ == ClockMode::System) return clock::ns_to_s(clock::system_ns());
  std::lock_guard<std::mutex> lock(mutex_);
  if (!last_tick_) return std::nullopt;
  const std::int64_t since_ns = clock::monotonic_ns() - last_tick_monotonic_ns_;
  return clock::ns_to_s(last_tick_->stamp_ns + since_ns);
}

}  // namespace cover::sim_clock

#include "lockstep_steps.hpp"

namespace cover::fc_bridge {

void LockstepSteps::flown(double tick_s) {
  flown_s_ = tick_s;
}

void LockstepSteps::frames_in(double step_s) {
  if (step_s <= in_s_) return;
  in_s_ = step_s;
  frames_in_.notify_all();
}

bool LockstepSteps::awaited_in(double tick_s) const {
  const bool none_awaited = flown_s_ < 0.0 || flown_s_ >= tick_s - kSameStep_s;
  return none_awaited || in_s_ >= flown_s_ - kSameStep_s;
}

bool LockstepSteps::wait(std::unique_lock<std::mutex>& lock, double tick_s,
                         std::chrono::steady_clock::time_point deadline) {
  return frames_in_.wait_until(lock, deadline, [&] { return awaited_in(tick_s); });
}

}  // namespace cover::fc_bridge

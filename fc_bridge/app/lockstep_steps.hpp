#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace cover::fc_bridge {

// Lockstep through an autopilot, made repeatable. The simulated autopilot flies a tick's
// setpoint for one step and then sends that step's frames, its HIGHRES_IMU last, stamped
// with the step's time. Those frames change what the bridge sends next (the hover-thrust
// estimate, mode and arm decisions) and what it reports on cover/uav/U/fc, so they must all
// be taken before the next tick's command is handled, whatever the threads' timing. The
// command's thread waits for the IMU of the step the last setpoint flew.
// Not locked itself: every call under the caller's mutex (the one `wait` is given).
class LockstepSteps {
 public:
  // A setpoint of tick `tick_s` went out: the autopilot flies it and sends that step's
  // frames.
  void flown(double tick_s);
  // The closing frame (HIGHRES_IMU) of step `step_s` was taken.
  void frames_in(double step_s);
  // Before the command of tick `tick_s`: waits until the frames of the step last flown
  // are in. No wait for a tick's repeat (that step is this tick) or before any setpoint.
  // False at `deadline`, with those frames still missing.
  bool wait(std::unique_lock<std::mutex>& lock, double tick_s,
            std::chrono::steady_clock::time_point deadline);

  double flown_s() const { return flown_s_; }  // -1: no setpoint yet
  double in_s() const { return in_s_; }        // the newest step whose frames are in; -1: none

 private:
  bool awaited_in(double tick_s) const;

  // Steps are whole control periods (>= 1 ms); IMU stamps are whole microseconds.
  static constexpr double kSameStep_s = 1e-4;
  std::condition_variable frames_in_;
  double flown_s_ = -1.0;
  double in_s_ = -1.0;
};

}  // namespace cover::fc_bridge

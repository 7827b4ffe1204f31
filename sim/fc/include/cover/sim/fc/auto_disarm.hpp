#pragma once

#include <optional>

#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

// Why an autopilot disarmed by itself.
enum class AutoDisarmCause {
  Px4Preflight,   // PX4: armed COM_DISARM_PRFLT + 1 s (spool-up) without taking off
  Px4Landed,      // PX4: landed COM_DISARM_LAND after a take-off, in any mode
  ArduPilotDelay  // ArduPilot: landed at zero throttle for DISARM_DELAY since arming
};

// What one armed step of the land detector and the auto-disarm rules found.
struct AutoDisarmStep {
  bool took_off = false;  // the land detector's landed -> in air
  bool landed = false;    // in air -> landed (after a take-off)
  std::optional<AutoDisarmCause> disarm;
};

// The firmwares' own auto-disarm, both measured with COVER's bridge (docs/autopilots.md, measured
// on real SITL): PX4 "Disarmed by preflight inaction" 11 s after arming on the ground and "Disarmed
// by landing" 2 s after touchdown (PX4 Commander: _auto_disarm_landed); ArduCopter "Disarming
// motors" DISARM_DELAY after arming when it stayed landed at zero throttle
// (motors.cpp auto_disarm_check). The simulator's land detector is the plant's contact:
// resting on a surface is landed.
class AutoDisarm {
 public:
  AutoDisarm(Autopilot profile, const SimFcParams& params);

  void on_armed(double now_s);
  // One step while armed: `landed` the plant rests on a surface, `throttle_zero` the
  // vehicle's throttle is at zero (ArduPilot's rule only).
  AutoDisarmStep step(double now_s, bool landed, bool throttle_zero);

 private:
  AutoDisarmStep px4_step(double now_s, bool landed);
  AutoDisarmStep ardupilot_step(double now_s, bool landed, bool throttle_zero);

  Autopilot profile_;
  double px4_preflight_s_;    // COM_DISARM_PRFLT + spool-up; <= 0: never
  double px4_landed_s_;       // COM_DISARM_LAND; <= 0: never
  double ardupilot_delay_s_;  // DISARM_DELAY; 0: never
  double armed_s_ = 0.0;
  bool taken_off_ = false;
  bool in_air_ = false;
  std::optional<double> landed_since_s_;
  double idle_since_s_ = 0.0;  // ArduPilot: landed at zero throttle since
};

}  // namespace cover::sim::fc

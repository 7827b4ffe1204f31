#include "cover/sim/fc/auto_disarm.hpp"

namespace cover::sim::fc {

namespace {
// PX4 adds its motors' spool-up (COM_SPOOLUP_TIME, 1 s) to COM_DISARM_PRFLT.
constexpr double kPx4SpoolUp_s = 1.0;
// Simulated time is a sum of control periods.
constexpr double kTimeTolerance_s = 1e-9;
}  // namespace

AutoDisarm::AutoDisarm(Autopilot profile, const SimFcParams& params)
    : profile_(profile),
      px4_preflight_s_(params.px4.com_disarm_prflt_s > 0.0
                           ? params.px4.com_disarm_prflt_s + kPx4SpoolUp_s
                           : 0.0),
      px4_landed_s_(params.px4.com_disarm_land_s),
      ardupilot_delay_s_(params.ardupilot.disarm_delay_s) {}

void AutoDisarm::on_armed(double now_s) {
  armed_s_ = now_s;
  taken_off_ = false;
  in_air_ = false;
  landed_since_s_.reset();
  idle_since_s_ = now_s;
}

AutoDisarmStep AutoDisarm::step(double now_s, bool landed, bool throttle_zero) {
  return profile_ == Autopilot::Px4 ? px4_step(now_s, landed)
                                    : ardupilot_step(now_s, landed, throttle_zero);
}

AutoDisarmStep AutoDisarm::px4_step(double now_s, bool landed) {
  AutoDisarmStep out;
  if (!landed) {
    out.took_off = !in_air_;
    in_air_ = true;
    taken_off_ = true;
    landed_since_s_.reset();
    return out;
  }
  if (in_air_) {
    out.landed = true;
    in_air_ = false;
    landed_since_s_ = now_s;
  }
  if (!taken_off_) {
    if (px4_preflight_s_ > 0.0 && now_s - armed_s_ + kTimeTolerance_s >= px4_preflight_s_) {
      out.disarm = AutoDisarmCause::Px4Preflight;
    }
  } else if (px4_landed_s_ > 0.0 && now_s - *landed_since_s_ + kTimeTolerance_s >= px4_landed_s_) {
    out.disarm = AutoDisarmCause::Px4Landed;
  }
  return out;
}

AutoDisarmStep AutoDisarm::ardupilot_step(double now_s, bool landed, bool throttle_zero) {
  AutoDisarmStep out;
  if (!landed || !throttle_zero) idle_since_s_ = now_s;
  if (ardupilot_delay_s_ > 0.0 && now_s - idle_since_s_ + kTimeTolerance_s >= ardupilot_delay_s_) {
    out.disarm = AutoDisarmCause::ArduPilotDelay;
  }
  return out;
}

}  // namespace cover::sim::fc

#pragma once
// What a firmware run's agent flies: COVER's kind of command (collective thrust and body
// rates), computed from what the firmware says of its own state (FirmwareMonitor), as
// cover-uav-agent computes it from its relative state.
#include <chrono>
#include <cstdint>

#include "cover/firmware/agent_stream.hpp"
#include "cover/firmware/firmware_monitor.hpp"

namespace cover::firmware {

constexpr double kGravity_m_s2 = 9.81;  // the bridge's gravity_m_s2

struct Euler {
  double roll = 0.0;  // rad, FRD body in NED
  double pitch = 0.0;
  double yaw = 0.0;
};
Euler euler(const mavlink::AttitudeQuaternion& q);

// Height above the firmware's local origin (LOCAL_POSITION_NED z is down), m.
inline double height_m(const mavlink::LocalPositionNed& p) {
  return -p.z;
}

AgentSetpoint motors_off();
// Thrust g, zero rates: a hover for a vehicle whose hover thrust the bridge knows.
AgentSetpoint hover();

// Climbs to and holds `height_m` above the local origin (vertical speed toward the height,
// thrust from the speed error) and levels the attitude with roll and pitch rates; the
// rates given in `extra` (FLU) are added, and the levelling is left out of an axis they use.
AgentStream::Policy hold_height(const FirmwareMonitor& monitor, double height_m,
                                AgentSetpoint extra = {});

// A roll-rate step of `rate` for `duration`, then zero rates for `pause`, then `-rate` for
// `duration` (back to the attitude it started from), thrust holding the height; from `start`
// (monotonic ns).
AgentStream::Policy roll_rate_doublet(const FirmwareMonitor& monitor, double height_m,
                                      std::int64_t start_ns, double rate,
                                      std::chrono::milliseconds duration,
                                      std::chrono::milliseconds pause);

}  // namespace cover::firmware

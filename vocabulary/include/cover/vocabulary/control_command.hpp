#pragma once

#include <Eigen/Core>

namespace cover::mission {

// Collective thrust per unit mass and body rates, plus the actuator flags.
struct ControlCommand {
  double thrust_m_s2 = 0.0;
  Eigen::Vector3d body_rate_rad_s = Eigen::Vector3d::Zero();
  bool armed = false;
  bool release_payload = false;  // open the airdrop on this step
  // The agent gives the UAV up to the flight controller's own landing: it has no relative
  // state left to land on (docs/failsafes.md). thrust/rates still carry its blind descent,
  // for a flight controller that ignores the flag.
  bool handover = false;
};

}  // namespace cover::mission

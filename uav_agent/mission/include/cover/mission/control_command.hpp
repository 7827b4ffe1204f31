#pragma once

#include <Eigen/Core>

namespace cover::mission {

// Collective thrust per unit mass and body rates, plus the actuator flags.
struct ControlCommand {
  double thrust_m_s2 = 0.0;
  Eigen::Vector3d body_rate_rad_s = Eigen::Vector3d::Zero();
  bool armed = false;
  bool release_payload = false;  // open the airdrop on this step
};

}  // namespace cover::mission

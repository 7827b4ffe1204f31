#pragma once

#include "cover/fc_bridge/autopilot_profile.hpp"

namespace cover::fc_bridge {

// The autopilot's state the bridge's decisions depend on, at one instant.
struct AutopilotView {
  bool link_ok = false;  // a HEARTBEAT within heartbeat_timeout_s
  bool armed = false;
  FcMode mode = FcMode::Unknown;
  // Armed, in OFFBOARD / GUIDED_NOGPS, link up: COVER's setpoints fly the UAV.
  bool cover_flying() const { return link_ok && armed && mode == FcMode::Offboard; }
};

}  // namespace cover::fc_bridge

#pragma once

#include <cstdint>

namespace cover::mission {

// The rungs of the failsafe ladder (failsafe_ladder.hpp), in the order a lost input climbs
// them. Landing and Disarmed are latched: the task has failed and only a new task starts a
// new ladder. What the UAV reports of them is its Failsafe (failsafe.hpp).
enum class LadderLevel : std::uint8_t {
  Nominal = 0,           // SAMPC flies the stage
  ImuHold = 1,           // SAMPC flies on the reference UGV's last IMU
  EmergencyHover = 2,    // level attitude, hover thrust, no position control
  EmergencyLanding = 3,  // level attitude, controlled sink, disarm on contact
  Disarmed = 4,          // touched down after an emergency landing: motors off
};

const char* to_string(LadderLevel level);

}  // namespace cover::mission

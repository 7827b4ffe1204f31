#pragma once

#include <cstdint>

namespace cover::mission {

// Why the command is not the optimised one: what a UAV reports in its status, and what the
// task manager reads to know whether the UAV can take a task.
enum class Failsafe : std::uint8_t {
  None = 0,
  WaitingForInputs = 1,   // no valid state/IMU of a UGV of the task yet: stay idle, disarmed
  EmergencyHover = 2,     // reference UGV's state or IMU lost or non-finite: level, hover thrust
  SolverError = 3,        // SAMPC returned its hover fallback
  MissionFailed = 4,      // the stage machine failed: hold position in the frame
  Landed = 5,             // disarmed on the landing point: motors idle
  Aborted = 6,            // the task was aborted: holding its point, then the safe action
  ImuHold = 7,            // reference UGV's IMU stale: SAMPC flies on its last sample
  EmergencyLanding = 8,   // inputs not back after the emergency hover: controlled descent
  EmergencyLanded = 9,    // disarmed on contact after an emergency landing
  AutopilotControl = 10,  // the flight controller does not fly COVER's setpoints: level hover
                          // command, nothing planned or integrated until it hands back
};

const char* to_string(Failsafe failsafe);

}  // namespace cover::mission

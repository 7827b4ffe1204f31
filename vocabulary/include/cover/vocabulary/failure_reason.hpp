#pragma once

#include <cstdint>

namespace cover::mission {

// Why a task failed (the stage machine's verdict, carried in every task status).
enum class FailureReason : std::uint8_t {
  None = 0,
  StageTimeout = 1,      // a stage did not end within its timeout
  InvalidState = 2,      // NaN / infinite relative state
  StaleInput = 3,        // relative state or UGV IMU too old for too long
  PlanningFailed = 4,    // the reference trajectory could not be generated
  AutopilotControl = 5,  // the flight controller left COVER's mode (a pilot took over, its
                         // own failsafe) or its link was lost
};

const char* to_string(FailureReason reason);

}  // namespace cover::mission

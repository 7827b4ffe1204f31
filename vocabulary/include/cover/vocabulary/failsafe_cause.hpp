#pragma once

#include <cstdint>

namespace cover::mission {

// What is wrong with the reference frame's inputs on one step (the first problem found).
enum class FailsafeCause : std::uint8_t {
  None = 0,
  ClockInvalid = 1,  // the step's time is not finite
  StateMissing = 2,  // no relative state of the reference UGV yet
  StateInvalid = 3,  // non-finite relative state
  StateStale = 4,    // relative state older than state_timeout_s
  ImuMissing = 5,
  ImuInvalid = 6,
  ImuStale = 7,  // UGV IMU older than imu_timeout_s (held up to imu_hold_s more)
};
const char* to_string(FailsafeCause cause);

}  // namespace cover::mission

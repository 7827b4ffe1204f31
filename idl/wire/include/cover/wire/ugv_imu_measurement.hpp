#pragma once

#include "cover/msg/types.hpp"
#include "cover/vocabulary/controller_input.hpp"

namespace cover::wire {

// A UGV agent's IMU as the UAV's controller takes it. A speed source the library does not
// know, or a non-finite speed, reads as no estimate (SpeedSource::None, speed 0): the
// controller then falls back to what needs no speed.
mission::UgvImuMeasurement from_msg(const msg::UgvImu& imu);

}  // namespace cover::wire

#pragma once

#include <cstdint>

#include "cover/firmware_link/plant_sample.hpp"
#include "cover/mavlink/hil_messages.hpp"

namespace cover::firmware_link {

// Where the world's origin is on the Earth, for the geodetic fields of PX4's ground truth
// (PX4 SITL's default home, Zurich).
struct GeodeticHome {
  double latitude_deg = 47.397742;
  double longitude_deg = 8.545594;
  double altitude_amsl_m = 488.0;
};

// The plant in PX4's frames: world ENU -> NED, (x, y, z) -> (y, x, -z); body FLU -> FRD,
// (x, y, z) -> (x, -y, -z), so a vehicle at rest reads specific force (0, 0, -g) FRD.
// `time_usec` is the firmware's clock; the sensor groups are those due in `sample`
// (IMU always: the frame exists because the IMU is due; + mag 448, + baro 6656), sensor id 0
// (PX4's primary IMU, the one that drives its lockstep clock).
mavlink::HilSensor hil_sensor(const PlantSample& sample, std::uint64_t time_usec);
// Ground truth for PX4's logs (HIL_STATE_QUATERNION: attitude FRD in NED, rates, the
// position as latitude / longitude / altitude about `home`, NED velocity, specific force).
mavlink::HilStateQuaternion hil_state_quaternion(const PlantSample& sample, std::uint64_t time_usec,
                                                 const GeodeticHome& home, double gravity_m_s2);

}  // namespace cover::firmware_link

#pragma once

#include <cstdint>
#include <optional>

#include "cover/mavlink/encoder.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::sim::fc {

// A UGV's own autopilot (a PX4 rover) as its IMU's MAVLink source: HIGHRES_IMU for every
// raw sample the simulator's IMU produces (time_usec = the sample's simulated time, FRD)
// and a HEARTBEAT (ground rover, PX4, manual mode) at `heartbeat_rate_hz`.
class SimulatedRoverImu {
 public:
  SimulatedRoverImu(std::uint8_t system_id, double heartbeat_rate_hz);

  mavlink::EncodedFrame imu_frame(const RawImuSample& sample);
  // The HEARTBEAT when one is due at `now_s` (simulated), else nullopt.
  std::optional<mavlink::EncodedFrame> heartbeat_due(double now_s);
  mavlink::EncodedFrame heartbeat_frame();

 private:
  mavlink::Encoder encoder_;
  double period_s_;
  double next_heartbeat_s_ = 0.0;
};

}  // namespace cover::sim::fc

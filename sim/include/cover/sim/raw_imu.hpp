#pragma once

#include "cover/vocabulary/ugv_imu.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::sim {

// A simulated IMU sample as the simulator writes it into the world segment's ring (the
// chip's output; the UGV agent reads it back in ugv/sim_shm_imu_source).
RawImuSample to_raw(const ugv::ImuSample& sample);

}  // namespace cover::sim

#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include "cover/shm/seqlock_writer.hpp"
#include "cover/sim/raw_imu.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::test {

// A run id no other test (process or case) uses: segments never collide.
inline std::string unique_run_id(const std::string& tag) {
  static int counter = 0;
  return tag + "_" + std::to_string(getpid()) + "_" + std::to_string(counter++);
}

// Sample i of a deterministic, non-trivial IMU trace at 200 Hz.
inline ugv::ImuSample trace_sample(int i) {
  const double t = 0.005 * i;
  ugv::ImuSample s;
  s.stamp_s = 10.0 + t;
  s.specific_force_m_s2 = {0.3 * std::sin(7.0 * t), 0.1 * std::cos(3.0 * t) + 0.01 * (i % 5),
                           9.81 + 0.05 * std::sin(40.0 * t)};
  s.angular_velocity_rad_s = {0.02 * std::sin(5.0 * t), -0.01 * t, 0.35 + 0.1 * std::sin(2.0 * t)};
  return s;
}

// Appends `sample` to UGV `ugv`'s ring as the simulator does: one seqlock write.
inline void append_sample(shm::SeqlockWriter<sim::SharedWorld>& writer, int ugv,
                          const ugv::ImuSample& sample) {
  writer.update(
      [&](sim::SharedWorld& world) {
        world.ugv_count = sim::kMaxUgvs;
        world.time_s = sample.stamp_s;
        sim::ImuRing& ring = world.imu[static_cast<std::size_t>(ugv)];
        ring.slots[ring.written % sim::kImuRingCapacity] = sim::to_raw(sample);
        ++ring.written;
      },
      static_cast<std::int64_t>(sample.stamp_s * 1e9));
}

inline std::string write_temp_file(const std::string& name, const std::string& text) {
  const std::string path = cover::test::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace cover::test

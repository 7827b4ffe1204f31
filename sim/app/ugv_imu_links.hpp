#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "autopilot_links.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"
#include "cover/sim/fc/simulated_rover_imu.hpp"
#include "cover/vocabulary/world_segment.hpp"

namespace cover::sim {

// Each UGV's IMU served as its own PX4 rover would serve it (cover-sim --ugv-imu mavlink):
// HIGHRES_IMU for every raw sample the simulator writes to the UGV's shared-memory ring
// and a HEARTBEAT at the configured rate, on UDP, UGV k binding bind_port_base + k and
// sending to peer_port_base + k. Sends only; used from one thread.
class UgvImuLinks {
 public:
  // Throws std::runtime_error naming a port that cannot be bound.
  UgvImuLinks(int ugv_count, MavlinkPorts ports, const fc::SimFcParams& params);

  // Sends the samples written to the rings since the last call, and the heartbeats due at
  // `now_s` (simulated).
  void send_new_samples(const SharedWorld& world, double now_s);
  // Sends the last call's samples again (a lockstep tick published again:
  // a lost datagram would otherwise hold up the UAV agents; the UGV agent drops a sample
  // whose stamp it has already had).
  void send_again();

  std::string describe(int ugv) const { return ugvs_[ugv].link->describe(); }
  std::uint64_t samples_sent() const { return samples_sent_; }

 private:
  struct Ugv {
    std::unique_ptr<mavlink::Link> link;
    fc::SimulatedRoverImu rover;
    std::uint64_t consumed = 0;              // ring samples sent
    std::vector<RawImuSample> last_samples;  // of the last call that had any
  };
  void send(Ugv& ugv, const mavlink::EncodedFrame& frame);

  std::vector<Ugv> ugvs_;
  std::uint64_t samples_sent_ = 0;
  std::uint64_t send_failures_ = 0;
};

}  // namespace cover::sim

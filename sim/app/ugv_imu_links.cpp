#include "ugv_imu_links.hpp"

namespace cover::sim {

UgvImuLinks::UgvImuLinks(int ugv_count, MavlinkPorts ports, const fc::SimFcParams& params) {
  for (int k = 0; k < ugv_count; ++k) {
    ugvs_.push_back(
        Ugv{open_sitl_link(static_cast<std::uint16_t>(ports.bind_port_base + k),
                           static_cast<std::uint16_t>(ports.peer_port_base + k)),
            fc::SimulatedRoverImu(static_cast<std::uint8_t>(params.ugv_system_id_base + k),
                                  params.px4.streams.heartbeat_hz),
            0,
            {}});
  }
}

void UgvImuLinks::send_new_samples(const SharedWorld& world, double now_s) {
  for (std::size_t k = 0; k < ugvs_.size(); ++k) {
    Ugv& ugv = ugvs_[k];
    if (const auto heartbeat = ugv.rover.heartbeat_due(now_s)) send(ugv, *heartbeat);
    const ImuRing& ring = world.imu[k];
    const std::uint64_t oldest =
        ring.written > kImuRingCapacity ? ring.written - kImuRingCapacity : 0;
    if (ugv.consumed < oldest) ugv.consumed = oldest;  // cannot happen at one call per tick
    if (ugv.consumed == ring.written) continue;
    ugv.last_samples.clear();
    for (; ugv.consumed < ring.written; ++ugv.consumed) {
      ugv.last_samples.push_back(ring.slots[ugv.consumed % kImuRingCapacity]);
      send(ugv, ugv.rover.imu_frame(ugv.last_samples.back()));
      ++samples_sent_;
    }
  }
}

void UgvImuLinks::send_again() {
  for (Ugv& ugv : ugvs_) {
    for (const RawImuSample& sample : ugv.last_samples) send(ugv, ugv.rover.imu_frame(sample));
  }
}

void UgvImuLinks::send(Ugv& ugv, const mavlink::EncodedFrame& frame) {
  if (!ugv.link->write(frame.bytes.data(), frame.size)) ++send_failures_;
}

}  // namespace cover::sim

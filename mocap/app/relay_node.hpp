#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/mocap/frame_assembler.hpp"
#include "cover/mocap/relative_estimator.hpp"
#include "cover/mocap/relay_params.hpp"
#include "cover/mocap/server_clock.hpp"
#include "cover/vrpn/tracker_client.hpp"

namespace cover::mocap {

// cover-mocap-relay's loop: VRPN reports in, one frame at a time through the estimator,
// every pair's relative state out on DDS, stamped with the frame's capture time on our
// clock.
class RelayNode {
 public:
  RelayNode(dds::Participant& participant, const RelayParams& params, vrpn::ClientOptions client);
  // Until SIGINT / SIGTERM.
  void run();

 private:
  void on_report(const vrpn::TrackerReport& report);
  void publish(const Frame& frame, std::int64_t completed_mono_ns);
  void write_outputs();
  void log_stats();

  RelayParams params_;
  vrpn::TrackerClient client_;
  FrameAssembler assembler_;
  RelativeEstimator estimator_;
  ServerClock server_clock_;
  std::vector<dds::Writer<msg::RelativeState>> writers_;  // one per pair, estimator's order
  std::vector<RelativeOutput> outputs_;
  // Relay-added latency: last message of a frame taken off the socket -> every pair
  // written, ns (a ring, summarised in the log).
  std::array<std::int64_t, 1024> latency_ns_{};
  std::uint64_t latency_count_ = 0;
  std::uint64_t published_frames_ = 0;
  std::uint64_t republished_frames_ = 0;
  std::int64_t republished_mono_ns_ = 0;
  std::uint64_t velocity_reports_ = 0;
  std::int64_t next_stats_mono_ns_ = 0;
};

}  // namespace cover::mocap

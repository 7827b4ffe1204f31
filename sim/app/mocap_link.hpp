#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cover/sim/mocap/mocap_feed.hpp"
#include "cover/sim/mocap/mocap_server_params.hpp"
#include "cover/sim/mocap/vrpn_server.hpp"

namespace cover::sim {

class Fleet;

// cover-sim --mocap vrpn[:PORT]: the simulator as a motion-capture system. Every
// vehicle's world pose is served as a VRPN tracker (ugv<k>, uav<u>); a cover-mocap-relay
// turns them into the relative states the simulator then no longer publishes.
struct MocapRunOptions {
  bool enabled = false;
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 3883;
  mocap::MocapServerParams params;
};

// "vrpn" or "vrpn:PORT" (empty: off) with the `mocap:` section of `config_file`; throws
// config::ConfigError naming the flag.
MocapRunOptions parse_mocap_option(const std::string& value, const std::string& config_file);

class MocapLink {
 public:
  // Throws std::runtime_error when the port cannot be bound.
  MocapLink(const Fleet& fleet, const MocapRunOptions& options);

  // Captures the fleet's poses on a new tick (once per tick), sends the frames whose
  // latency has passed (none while `withheld`), and returns the newest capture time sent,
  // ns (-1: none yet): the tick's relative_stamp_ns. Called again for the same tick (the
  // tick published again), it sends that newest frame again.
  std::int64_t serve(const Fleet& fleet, bool withheld);
  bool wait_for_client(std::chrono::milliseconds timeout) const;
  std::string describe() const;

 private:
  MocapRunOptions options_;
  mocap::VrpnServer server_;
  mocap::MocapFeed feed_;
  std::vector<mocap::BodyTruth> truth_;
  std::vector<mocap::MocapFrame> released_;
  std::uint64_t served_tick_ = UINT64_MAX;
  std::int64_t newest_sent_ns_ = -1;
  std::optional<mocap::MocapFrame> last_sent_;
};

}  // namespace cover::sim

#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/foxglove/scene.hpp"
#include "cover/foxglove/server.hpp"
#include "cover/recording/fleet_tap.hpp"

namespace cover::foxglove_bridge {

struct BridgeOptions {
  foxglove::ServerOptions server;
  recording::FleetTapOptions tap;
  foxglove::SceneOptions scene;
  double scene_rate_hz = 20.0;  // FrameTransforms and SceneUpdate, while subscribed
};

// The live view: every catalogued topic the globs select advertised as a channel (encoding
// cdr, schemaEncoding omgidl, the type's IDL text) and streamed to its subscribers as the
// CDR that crossed the wire; plus cover/foxglove/tf (foxglove.FrameTransform) and
// cover/foxglove/scene (foxglove.SceneUpdate) from the relative states and references.
// A topic nobody subscribes to costs a callback that returns at once.
class BridgeNode {
 public:
  // Throws std::runtime_error when the port cannot be listened on, dds::DdsError when a
  // reader cannot be made.
  BridgeNode(dds::Participant& participant, const BridgeOptions& options);
  ~BridgeNode();
  // Publishes the 3D channels and logs statistics until SIGINT/SIGTERM.
  void run();
  std::uint16_t port() const { return server_.port(); }

 private:
  void publish_scene(std::int64_t now_ns);
  void log_stats();

  BridgeOptions options_;
  foxglove::Server server_;
  foxglove::Scene scene_;
  std::uint32_t tf_channel_ = 0;
  std::uint32_t scene_channel_ = 0;
  std::vector<std::uint32_t> channel_of_topic_;  // by FleetTap topic index; fixed once ready_
  std::atomic<bool> ready_{false};
  std::atomic<std::uint64_t> forwarded_{0};
  std::atomic<std::uint64_t> unserializable_{0};
  std::vector<dds::Reader<msg::RelativeState>> relative_readers_;
  std::vector<dds::Reader<msg::ReferenceTrajectory>> reference_readers_;
  std::unique_ptr<recording::FleetTap> tap_;  // last: its callbacks use the members above
};

}  // namespace cover::foxglove_bridge

#include "bridge_node.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "cover/clock/clock.hpp"
#include "cover/dds/topics.hpp"
#include "cover/foxglove/foxglove_schemas.hpp"
#include "cover/msg/idl_schema.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::foxglove_bridge {
namespace {

constexpr std::int64_t kStatsPeriodNs = 10'000'000'000;
constexpr const char* kTfTopic = "cover/foxglove/tf";
constexpr const char* kSceneTopic = "cover/foxglove/scene";

}  // namespace

BridgeNode::BridgeNode(dds::Participant& participant, const BridgeOptions& options)
    : options_(options), server_(options.server), scene_(options.scene) {
  const auto ids =
      server_.add_channels({foxglove::json_channel(kTfTopic, foxglove::kFrameTransformSchema),
                            foxglove::json_channel(kSceneTopic, foxglove::kSceneUpdateSchema)});
  tf_channel_ = ids[0];
  scene_channel_ = ids[1];
  // The scene's own readers (typed): UAV poses in each UGV frame, and the references.
  for (std::uint32_t u = 0; u < options.scene.uavs; ++u) {
    for (std::uint32_t k = 0; k < options.scene.ugvs; ++k) {
      relative_readers_.push_back(
          participant.make_reader(dds::topics::relative_state(u, k).without_deadline(),
                                  [this](const msg::RelativeState& s) {
                                    scene_.on_relative_state(s, clock::system_ns());
                                  }));
    }
    reference_readers_.push_back(participant.make_reader(
        dds::topics::uav_reference(u),
        [this](const msg::ReferenceTrajectory& r) { scene_.on_reference(r); }));
  }
  tap_ = std::make_unique<recording::FleetTap>(
      participant, options.tap,
      [this](recording::TapSample&& sample) {
        if (sample.bytes.empty()) {
          ++unserializable_;
          return;
        }
        ++forwarded_;
        server_.publish(channel_of_topic_[sample.topic_index],
                        static_cast<std::uint64_t>(sample.received_ns), sample.bytes.data(),
                        sample.bytes.size());
      },
      [this](std::uint32_t index) {
        return ready_.load(std::memory_order_acquire) &&
               server_.has_subscribers(channel_of_topic_[index]);
      });
  std::vector<foxglove::Channel> channels;
  for (const auto& topic : tap_->topics()) {
    foxglove::Channel c;
    c.topic = topic.name;
    c.encoding = "cdr";
    c.schema_name = topic.type_name;
    c.schema = std::string(msg::idl_schema(topic.type_name));
    c.schema_encoding = "omgidl";
    channels.push_back(std::move(c));
  }
  channel_of_topic_ = server_.add_channels(std::move(channels));
  ready_.store(true, std::memory_order_release);
  spdlog::info(
      "serving {} DDS topics and {} / {} on ws://{}:{} (queue {} KiB per client, a "
      "client full for {:.1f} s is dropped, at most {} clients)",
      channel_of_topic_.size(), kTfTopic, kSceneTopic, options.server.transport.address,
      server_.port(), options.server.transport.client_queue_bytes / 1024,
      options.server.transport.slow_client_timeout_s, options.server.transport.max_clients);
}

BridgeNode::~BridgeNode() {
  tap_->stop();  // no DDS callback past this line
  relative_readers_.clear();
  reference_readers_.clear();
  server_.stop();
}

void BridgeNode::publish_scene(std::int64_t now_ns) {
  if (server_.has_subscribers(tf_channel_)) {
    for (const auto& transform : scene_.frame_transforms(now_ns)) {
      server_.publish(tf_channel_, static_cast<std::uint64_t>(now_ns),
                      reinterpret_cast<const std::uint8_t*>(transform.data()), transform.size());
    }
  }
  if (server_.has_subscribers(scene_channel_)) {
    const std::string update = scene_.scene_update(now_ns);
    server_.publish(scene_channel_, static_cast<std::uint64_t>(now_ns),
                    reinterpret_cast<const std::uint8_t*>(update.data()), update.size());
  }
}

void BridgeNode::log_stats() {
  const auto s = server_.stats();
  spdlog::info(
      "{} clients ({} since start); {} samples forwarded, {} frames queued ({:.1f} MiB), "
      "{} dropped for full client queues, {} slow clients disconnected, {} bad client "
      "messages, {} unserializable samples",
      s.clients, s.connections, forwarded_.load(), s.messages_sent,
      static_cast<double>(s.bytes_sent) / (1024.0 * 1024.0), s.dropped, s.slow_disconnects,
      s.bad_messages, unserializable_.load());
}

void BridgeNode::run() {
  const auto period =
      std::chrono::milliseconds(static_cast<long>(1000.0 / std::max(options_.scene_rate_hz, 0.1)));
  std::int64_t next_stats_ns = clock::monotonic_ns() + kStatsPeriodNs;
  while (!process::ShutdownSignal::wait_for(period)) {
    publish_scene(clock::system_ns());
    if (clock::monotonic_ns() >= next_stats_ns) {
      log_stats();
      next_stats_ns += kStatsPeriodNs;
    }
  }
  log_stats();
}

}  // namespace cover::foxglove_bridge

#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/fleet_size.hpp"

namespace cover::foxglove {

struct SceneOptions {
  std::uint32_t uavs = fleet::kDefaultUavs;
  std::uint32_t ugvs = fleet::kDefaultUgvs;
  // A relative state older than this (by its receive time) no longer places a frame.
  double stale_after_s = 0.5;
  double deck_size_m = 1.0;  // the square drawn at each UGV frame's origin
};

// The fleet in Foxglove's 3D types, from the data a real flight has (no simulator truth):
// the relative states cover/uav/<u>/rel/<k> give UAV u's pose in each UGV frame G_k, so
// the frames form a graph with an edge per fresh valid state. Its spanning forest (rooted
// at the lowest UGV of each component, breadth first) is published as one
// foxglove.FrameTransform per frame that has a parent: ugv_<k> -> uav_<u> is the state
// itself, uav_<u> -> ugv_<j> its inverse. A user can pick any UGV frame as the display
// frame and see every UAV and deck the states connect to it.
// The scene (foxglove.SceneUpdate): each UAV, each deck, and each UAV's current reference
// path (cover/uav/<u>/reference, in its reference UGV's frame). Thread-safe: the inputs
// come from DDS receive threads, the outputs are built by the bridge's loop.
class Scene {
 public:
  explicit Scene(SceneOptions options);

  static std::string ugv_frame(std::uint32_t k) { return "ugv_" + std::to_string(k); }
  static std::string uav_frame(std::uint32_t u) { return "uav_" + std::to_string(u); }

  void on_relative_state(const msg::RelativeState& state, std::int64_t received_ns);
  void on_reference(const msg::ReferenceTrajectory& reference);

  // JSON foxglove.FrameTransform messages, stamped `now_ns` (the bridge's system clock,
  // the clock of the messages' log times, so Foxglove finds each transform at the time of
  // the scene entities).
  std::vector<std::string> frame_transforms(std::int64_t now_ns) const;
  // A JSON foxglove.SceneUpdate of every frame frame_transforms() reaches.
  std::string scene_update(std::int64_t now_ns) const;

 private:
  struct Edge {
    std::uint32_t uav;
    std::uint32_t ugv;
  };
  struct Transform {
    std::string parent;
    std::string child;
    msg::Vector3 translation;
    msg::Quaternion rotation;
  };
  std::vector<Transform> spanning_forest(std::int64_t now_ns) const;  // under mutex_

  SceneOptions options_;
  mutable std::mutex mutex_;
  std::vector<std::optional<msg::RelativeState>> states_;  // [u * ugvs + k]
  std::vector<std::int64_t> received_ns_;
  std::vector<std::optional<msg::ReferenceTrajectory>> references_;  // [u]
};

}  // namespace cover::foxglove

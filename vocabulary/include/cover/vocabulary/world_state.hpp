#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "cover/vocabulary/fleet_size.hpp"
#include "cover/vocabulary/pod_types.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::sim {

// The world is a fixed-capacity plain struct (no pointers, no heap), sized by the fleet's
// limits, so that it copies into a shared-memory segment as is.
using fleet::kMaxUgvs;

// A planar UGV in the world frame. Its body frame G_k has its origin at the deck centre
// (height `position_m.z`), x forward, z up, yaw only.
struct UgvState {
  Vec3 position_m;
  Vec3 velocity_m_s;
  Vec3 acceleration_m_s2;
  double yaw_rad = 0.0;
  double yaw_rate_rad_s = 0.0;
  double yaw_acceleration_rad_s2 = 0.0;

  Eigen::Quaterniond attitude() const { return yaw_quaternion(yaw_rad); }
  // Omega and beta of the paper, expressed in G_k (planar: along z).
  Eigen::Vector3d angular_velocity_in_body_rad_s() const { return {0.0, 0.0, yaw_rate_rad_s}; }
  Eigen::Vector3d angular_acceleration_in_body_rad_s2() const {
    return {0.0, 0.0, yaw_acceleration_rad_s2};
  }
  // World-frame velocity of the deck point at world position `point_m` (rigid body).
  Eigen::Vector3d point_velocity_m_s(const Eigen::Vector3d& point_m) const {
    return velocity_m_s.eigen() +
           Eigen::Vector3d(0.0, 0.0, yaw_rate_rad_s).cross(point_m - position_m.eigen());
  }
  // A point given in G_k, in world coordinates.
  Eigen::Vector3d to_world(const Eigen::Vector3d& point_in_body_m) const {
    return position_m.eigen() + attitude() * point_in_body_m;
  }
  Eigen::Vector3d to_body(const Eigen::Vector3d& point_in_world_m) const {
    return attitude().inverse() * (point_in_world_m - position_m.eigen());
  }
};

// Which surface holds the UAV (or the payload) up, if any.
struct ContactState {
  bool resting = false;       // sitting on a surface (moves with it)
  std::int32_t surface = -1;  // -1: ground, k >= 0: deck of UGV k (valid when resting)
  Vec3 offset_in_surface_m;   // position in the surface's frame while resting
  double yaw_offset_rad = 0.0;
};

struct PayloadState {
  bool attached = false;  // hanging on the UAV (its mass adds to the UAV's)
  bool released = false;
  double release_time_s = 0.0;
  Vec3 release_position_m;  // world frame, where the UAV let go
  // The release point seen in every UGV frame: the delivery error of the benchmarks.
  std::array<Vec3, kMaxUgvs> release_position_in_ugv_m{};
  Vec3 position_m;  // world; follows the UAV while attached, falls after release
  Vec3 velocity_m_s;
  ContactState contact;  // where it came to rest after falling
};

struct WorldState {
  double time_s = 0.0;
  std::uint64_t step_index = 0;
  std::int32_t ugv_count = 0;
  std::array<UgvState, kMaxUgvs> ugvs{};
  QuadrotorState uav;
  ContactState uav_contact;
  PayloadState payload;
  QuadrotorCommand last_command;  // the command the plant is holding (after rejection checks)
};

static_assert(std::is_trivially_copyable_v<WorldState>,
              "WorldState must stay memcpy-able for the shared-memory simulator");

}  // namespace cover::sim

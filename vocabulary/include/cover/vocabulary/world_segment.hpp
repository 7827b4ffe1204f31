#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// The world as cover-sim shares it through POSIX shared memory (services/shm, seqlock):
// ground truth for tests and viewers, and each UGV's raw IMU, which the UGV agents read
// as they would read their device. Fixed capacity, no pointers: memcpy-able. Bump the
// layout version whenever a field changes.
inline constexpr std::uint32_t kWorldSegmentLayoutVersion = 3;
using fleet::kMaxUavs;
// Raw IMU samples kept per UGV: 64 at 200 Hz is 320 ms, far more than a reader lags.
inline constexpr int kImuRingCapacity = 64;

// One raw IMU sample (what the chip outputs), in G_k, and the wheel odometry's forward
// speed when it was read with this sample (UGVs with odometry, at the odometry rate).
struct RawImuSample {
  double stamp_s = 0.0;
  Vec3 specific_force_m_s2;
  Vec3 angular_velocity_rad_s;
  std::uint8_t has_wheel_speed = 0;  // 1: wheel_speed_m_s was read with this sample
  double wheel_speed_m_s = 0.0;
};

// Sample n (0-based, counted since the start) lives in slots[n % kImuRingCapacity].
struct ImuRing {
  std::uint64_t written = 0;
  std::array<RawImuSample, kImuRingCapacity> slots{};
};

// Why the simulated flight controller ignores the agent (PX4's offboard-loss failsafe).
enum class OffboardState : std::uint8_t {
  WaitingForAgent = 0,  // no command yet: motors off
  Offboard = 1,         // flying the agent's commands
  LossDescent = 2,      // no fresh command for offboard_timeout_s: level, descend, disarm
  LossDisarmed = 3,     // touched down during the loss descent: motors off
};
const char* to_string(OffboardState state);

struct SharedUav {
  QuadrotorState state;
  ContactState contact;
  PayloadState payload;
  QuadrotorCommand command;  // what the plant holds
  OffboardState offboard = OffboardState::WaitingForAgent;
};

struct SharedWorld {
  double time_s = 0.0;
  std::uint64_t tick = 0;  // control periods since start
  std::int32_t ugv_count = 0;
  std::int32_t uav_count = 0;
  std::array<UgvState, kMaxUgvs> ugvs{};
  std::array<SharedUav, kMaxUavs> uavs{};
  std::array<ImuRing, kMaxUgvs> imu{};
};

static_assert(std::is_trivially_copyable_v<SharedWorld>);

}  // namespace cover::sim

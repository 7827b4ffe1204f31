#pragma once

#include <cstdint>

namespace cover::mavlink {

// What an autopilot says about its estimator and its motion: the health of its state
// estimate (PX4's ESTIMATOR_STATUS, ArduPilot's EKF_STATUS_REPORT) and its local velocity
// (LOCAL_POSITION_NED, NED metres and m/s). EKF_STATUS_REPORT is ardupilotmega.xml's.

// ESTIMATOR_STATUS_FLAGS / EKF_STATUS_FLAGS share their low bits.
namespace estimator_flags {
inline constexpr std::uint16_t kAttitude = 1;
inline constexpr std::uint16_t kVelocityHoriz = 2;
inline constexpr std::uint16_t kVelocityVert = 4;
inline constexpr std::uint16_t kPosHorizRel = 8;
inline constexpr std::uint16_t kPosHorizAbs = 16;
inline constexpr std::uint16_t kPosVertAbs = 32;
inline constexpr std::uint16_t kPosVertAgl = 64;
inline constexpr std::uint16_t kConstPosMode = 128;
inline constexpr std::uint16_t kPredPosHorizRel = 256;
inline constexpr std::uint16_t kPredPosHorizAbs = 512;
inline constexpr std::uint16_t kGpsGlitch = 1024;
inline constexpr std::uint16_t kAccelError = 2048;
}  // namespace estimator_flags

struct EstimatorStatus {
  static constexpr std::uint32_t kId = 230;
  static constexpr std::uint8_t kCrcExtra = 163;
  static constexpr std::uint8_t kPayloadLength = 42;
  std::uint64_t time_usec = 0;
  float vel_ratio = 0.0F;
  float pos_horiz_ratio = 0.0F;
  float pos_vert_ratio = 0.0F;
  float mag_ratio = 0.0F;
  float hagl_ratio = 0.0F;
  float tas_ratio = 0.0F;
  float pos_horiz_accuracy = 0.0F;  // m
  float pos_vert_accuracy = 0.0F;   // m
  std::uint16_t flags = 0;          // ESTIMATOR_STATUS_FLAGS
  void pack(std::uint8_t* payload) const;
  static EstimatorStatus unpack(const std::uint8_t* payload);
};

struct EkfStatusReport {
  static constexpr std::uint32_t kId = 193;
  static constexpr std::uint8_t kCrcExtra = 71;
  static constexpr std::uint8_t kPayloadLength = 26;
  float velocity_variance = 0.0F;
  float pos_horiz_variance = 0.0F;
  float pos_vert_variance = 0.0F;
  float compass_variance = 0.0F;
  float terrain_alt_variance = 0.0F;
  std::uint16_t flags = 0;  // EKF_STATUS_FLAGS
  // extensions
  float airspeed_variance = 0.0F;
  void pack(std::uint8_t* payload) const;
  static EkfStatusReport unpack(const std::uint8_t* payload);
};

struct LocalPositionNed {
  static constexpr std::uint32_t kId = 32;
  static constexpr std::uint8_t kCrcExtra = 185;
  static constexpr std::uint8_t kPayloadLength = 28;
  std::uint32_t time_boot_ms = 0;
  float x = 0.0F, y = 0.0F, z = 0.0F;     // m, NED
  float vx = 0.0F, vy = 0.0F, vz = 0.0F;  // m/s, NED (vz > 0: descending)
  void pack(std::uint8_t* payload) const;
  static LocalPositionNed unpack(const std::uint8_t* payload);
};

}  // namespace cover::mavlink

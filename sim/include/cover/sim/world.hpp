#pragma once

#include <cstdint>
#include <optional>

#include "cover/sim/firmware_uav_params.hpp"
#include "cover/sim/imu_sensor.hpp"
#include "cover/sim/motor_uav.hpp"
#include "cover/sim/odometry_sensor.hpp"
#include "cover/sim/quadrotor.hpp"
#include "cover/sim/relative_sensor.hpp"
#include "cover/sim/surface_contact.hpp"
#include "cover/sim/ugv_motion_pattern.hpp"
#include "cover/sim/world_params.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

enum class StepStatus : std::uint8_t {
  Ok,
  CommandRejected,  // non-finite command: the plant kept the last accepted one
};
const char* to_string(StepStatus status);

// The world-frame simulation: N UGVs on analytic patterns, one quadrotor plant with
// ground/deck contact, an optional payload, and the sensors the UAV and UGV agents see.
// Fixed-step (RK4 at physics_rate_hz), seeded and deterministic: two Worlds built from
// the same params and fed the same commands produce bit-identical states.
//
// Contact model (surface_contact.hpp): the ground (z = 0) and each UGV's deck are rigid and
// perfectly inelastic; a UAV without the thrust to lift off rests on one, carried along.
class World {
 public:
  // Validates `params` (throws cover::config::ConfigError at construction, never later).
  explicit World(const WorldParams& params);
  // A world whose UAV is the motor-level quadrotor a real firmware flies (motor_uav.hpp):
  // step it with the firmware's motor outputs, not with rate commands.
  World(const WorldParams& params, const FirmwareUavParams& firmware_uav);

  // One physics step of 1 / physics_rate_hz, holding `command` (zero-order hold).
  StepStatus step(const QuadrotorCommand& command);
  // Whole steps covering `duration_s`; returns CommandRejected if the command was.
  StepStatus advance(const QuadrotorCommand& command, double duration_s);

  // Motor-level UAV only (has_motor_uav()). One physics step holding `outputs`.
  void step(const MotorOutputs& outputs);
  // One physics step of the UAV alone, on the firmware's clock: the world's time and the
  // UGVs stand still (their decks held at rest, without their initial speeds), so that a
  // firmware booting on a deck sees a vehicle at rest (PX4 aligns only below 15 deg/s).
  // The first step() after it carries the UAV off with its deck.
  void settle_uav(const MotorOutputs& outputs);
  bool has_motor_uav() const { return motor_uav_.has_value(); }
  const MotorUav& motor_uav() const { return *motor_uav_; }

  // Opens the airdrop: records the release point (world and every G_k) and lets the
  // payload fall. Returns false when no payload is attached.
  bool release_payload();

  const WorldState& state() const { return state_; }
  const WorldParams& params() const { return params_; }
  double physics_dt_s() const { return dt_s_; }
  int ugv_count() const { return state_.ugv_count; }

  // Ground truth for metrics and tests (the controller must use the sensors instead).
  RelativeState true_relative_state(int ugv_index) const;
  // The F that hovers the true (heavier) UAV, in the command's unit.
  double hover_thrust_command_m_s2() const;

  const RelativeSensor& relative_sensor() const { return relative_sensor_; }
  const ImuSensor& imu_sensor() const { return imu_sensor_; }
  const OdometrySensor& odometry_sensor() const { return odometry_sensor_; }
  const Quadrotor& quadrotor() const { return quadrotor_; }

 private:
  void update_ugvs();
  void update_uav(const QuadrotorCommand& command);
  void place_uav_at_start();
  void update_payload();
  void update_sensors();

  double extra_mass_kg() const;
  SurfaceContact surfaces() const;

  WorldParams params_;
  std::int64_t dt_ns_;  // the physics step in whole nanoseconds
  double dt_s_;
  Quadrotor quadrotor_;
  std::vector<UgvMotionPattern> patterns_;
  RelativeSensor relative_sensor_;
  OdometrySensor odometry_sensor_;
  ImuSensor imu_sensor_;
  std::optional<MotorUav> motor_uav_;
  bool settling_ = false;  // the last step was settle_uav()
  bool ugvs_held_ = false;
  double ugv_clock_lag_s_ = 0.0;
  double held_ugv_time_s_ = 0.0;  // the world's time minus the UGV patterns' time
  WorldState state_;
};

}  // namespace cover::sim

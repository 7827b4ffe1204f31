#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "cover/sim/firmware_uav_params.hpp"
#include "cover/sim/motor_quadrotor.hpp"
#include "cover/sim/surface_contact.hpp"
#include "cover/sim/uav_sensor_suite.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// The UAV a real firmware flies, as the World's plant: the motor-level quadrotor, its
// contact with the ground and the decks, and the sensors the firmware's estimator reads.
// It keeps the firmware's clock (its steps since boot), which runs on while the world's
// clock waits (World::settle_uav: the firmware aligns on a still deck before the UGVs move).
class MotorUav {
 public:
  // `params` must have passed validate(physics_rate_hz).
  MotorUav(const FirmwareUavParams& params, double physics_rate_hz, double gravity_m_s2,
           std::uint64_t seed);

  // The outputs held from the next step on, in the firmware's output order, [0, 1].
  void command(const MotorOutputs& outputs) { outputs_ = outputs; }
  // One physics step of `body` (its contact resolved against `surfaces`), then the sensors
  // due on the firmware's clock.
  void step(QuadrotorState& body, ContactState& contact, const SurfaceContact& surfaces,
            double extra_mass_kg);
  // Rotors spun up to hold `extra_mass_kg` in hover (a mid-air start).
  void spin_up_to_hover(QuadrotorState& body, double extra_mass_kg);
  // The next resting step takes its acceleration as the surface's from scratch (the surface
  // jumped, e.g. a still deck starting to move).
  void forget_motion() { was_resting_ = false; }

  // What the last step produced.
  const UavSensorFrame& sensors() const { return sensors_; }
  const Eigen::Vector3d& acceleration_world_m_s2() const { return acceleration_world_m_s2_; }
  const MotorOutputs& outputs() const { return outputs_; }
  const std::array<double, kRotorCount>& rotor_speed_rad_s() const { return rotor_speed_rad_s_; }

  // The firmware's clock: physics steps since it booted, and that many steps in seconds.
  std::uint64_t firmware_step() const { return firmware_step_; }
  double firmware_time_s() const;
  double dt_s() const { return dt_s_; }
  double mass_kg() const { return plant_.params().mass_kg; }
  const MotorQuadrotor& plant() const { return plant_; }

 private:
  Eigen::Vector3d acceleration_after_step(const QuadrotorState& before, const QuadrotorState& after,
                                          bool resting, double extra_mass_kg) const;

  MotorQuadrotor plant_;
  UavSensorSuite sensor_suite_;
  double gravity_m_s2_;
  std::int64_t dt_ns_;
  double dt_s_;
  MotorOutputs outputs_{};
  std::array<double, kRotorCount> rotor_speed_rad_s_{};
  std::uint64_t firmware_step_ = 0;
  bool was_resting_ = false;
  UavSensorFrame sensors_;
  Eigen::Vector3d acceleration_world_m_s2_ = Eigen::Vector3d::Zero();
};

}  // namespace cover::sim

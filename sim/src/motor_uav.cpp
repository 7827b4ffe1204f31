#include "cover/sim/motor_uav.hpp"

#include <cmath>

#include "cover/clock/clock.hpp"

namespace cover::sim {

MotorUav::MotorUav(const FirmwareUavParams& params, double physics_rate_hz, double gravity_m_s2,
                   std::uint64_t seed)
    : plant_(params.plant),
      sensor_suite_(params.sensors, physics_rate_hz, gravity_m_s2, seed),
      gravity_m_s2_(gravity_m_s2),
      dt_ns_(std::llround(1e9 / physics_rate_hz)),
      dt_s_(clock::ns_to_s(dt_ns_)) {}

double MotorUav::firmware_time_s() const {
  return clock::ns_to_s(static_cast<std::int64_t>(firmware_step_) * dt_ns_);
}

void MotorUav::step(QuadrotorState& body, ContactState& contact, const SurfaceContact& surfaces,
                    double extra_mass_kg) {
  const QuadrotorState before = body;
  MotorQuadrotorState state{body, rotor_speed_rad_s_};
  plant_.step(state, outputs_, extra_mass_kg, gravity_m_s2_, dt_s_);
  body = state.body;
  rotor_speed_rad_s_ = state.rotor_speed_rad_s;
  surfaces.resolve(body, contact, mass_kg() + extra_mass_kg, gravity_m_s2_);

  acceleration_world_m_s2_ = acceleration_after_step(before, body, contact.resting, extra_mass_kg);
  was_resting_ = contact.resting;
  ++firmware_step_;
  sensors_ =
      sensor_suite_.update(firmware_step_, firmware_time_s(), body, acceleration_world_m_s2_);
}

// In flight the plant's own acceleration. Resting, the surface's: the change of the carried
// velocity over the step, except on the step that began the rest (a touchdown's velocity
// jump is an impulse the landing gear absorbs, not a reading the IMU could give).
Eigen::Vector3d MotorUav::acceleration_after_step(const QuadrotorState& before,
                                                  const QuadrotorState& after, bool resting,
                                                  double extra_mass_kg) const {
  if (!resting) {
    MotorQuadrotorState state{after, rotor_speed_rad_s_};
    return plant_.linear_acceleration_m_s2(state, extra_mass_kg, gravity_m_s2_);
  }
  if (!was_resting_) return Eigen::Vector3d::Zero();
  return (after.velocity_m_s.eigen() - before.velocity_m_s.eigen()) / dt_s_;
}

void MotorUav::spin_up_to_hover(QuadrotorState& body, double extra_mass_kg) {
  const double hover = plant_.hover_output(extra_mass_kg, gravity_m_s2_);
  outputs_.fill(hover);
  rotor_speed_rad_s_ = plant_.steady_rotor_speeds(outputs_);
  body.thrust_n = (mass_kg() + extra_mass_kg) * gravity_m_s2_;
}

}  // namespace cover::sim

#pragma once

#include <Eigen/Core>

#include "cover/config/yaml_reader.hpp"
#include "cover/sim/quadrotor_state.hpp"

namespace cover::sim {

// The "true" quadrotor, deliberately different from what the controller assumes
// (perfect body-rate tracking, F = thrust / mass_nominal, no drag): a first-order rate
// loop with limits, a thrust lag, linear drag and a heavier true mass.
struct QuadrotorParams {
  double mass_nominal_kg = 1.0;  // what the controller believes (F = thrust / this)
  double mass_true_kg = 1.05;    // the plant: +5 % by default
  // Linear rotor/body drag per unit mass in the body frame, 1/s: a = -R diag(d) R^T v.
  Eigen::Vector3d drag_coefficients_1_s = Eigen::Vector3d(0.3, 0.3, 0.1);
  double rate_time_constant_s = 0.03;    // body-rate loop, first order
  double thrust_time_constant_s = 0.02;  // motor spin-up lag, first order
  // Command limits, applied before the lags. Thrust is per NOMINAL mass (the command's unit).
  double min_thrust_m_s2 = 0.0;
  double max_thrust_m_s2 = 20.0;
  double max_roll_pitch_rate_rad_s = 6.0;
  double max_yaw_rate_rad_s = 3.0;

  static QuadrotorParams load(cover::config::YamlReader& reader);
  void validate(const std::string& context = "uav") const;
};

class Quadrotor {
 public:
  // `params` must have passed validate().
  explicit Quadrotor(const QuadrotorParams& params);

  // One RK4 step of length dt_s with the command held (zero-order hold). `extra_mass_kg`
  // is an attached payload. The command must be finite (the World checks it).
  void step(QuadrotorState& state, const QuadrotorCommand& command, double extra_mass_kg,
            double gravity_m_s2, double dt_s) const;

  // Collective thrust that holds `state` in hover with the true mass: what a perfect
  // controller would command, in the command's unit (per nominal mass).
  double hover_thrust_command_m_s2(double extra_mass_kg, double gravity_m_s2) const;

  // Command after the plant's limits (what the lags actually chase).
  QuadrotorCommand saturate(const QuadrotorCommand& command) const;

  const QuadrotorParams& params() const { return params_; }

 private:
  QuadrotorParams params_;
};

}  // namespace cover::sim

#pragma once

#include <Eigen/Core>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

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

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("mass_nominal_kg", self.mass_nominal_kg,
          Field("kg", "mass the controller assumes (F = thrust / this)")
              .at_least(0.01)
              .at_most(100.0));
    visit("mass_true_kg", self.mass_true_kg,
          Field("kg", "the plant's real mass").at_least(0.01).at_most(100.0));
    visit("drag_coefficients_1_s", self.drag_coefficients_1_s,
          Field("1/s", "linear drag per unit mass in body x, y, z").at_least(0.0).at_most(10.0));
    // The lags must be resolved by a 1 kHz RK4 step; below 2 ms they would be stiff.
    visit("rate_time_constant_s", self.rate_time_constant_s,
          Field("s", "first-order body-rate loop time constant").at_least(0.002).at_most(1.0));
    visit("thrust_time_constant_s", self.thrust_time_constant_s,
          Field("s", "first-order motor/thrust lag").at_least(0.002).at_most(1.0));
    visit("min_thrust_m_s2", self.min_thrust_m_s2,
          Field("m/s^2", "lowest collective thrust command per nominal mass")
              .at_least(0.0)
              .at_most(100.0));
    visit(
        "max_thrust_m_s2", self.max_thrust_m_s2,
        Field("m/s^2", "highest collective thrust command per nominal mass, above min_thrust_m_s2")
            .at_least(0.0)
            .at_most(100.0));
    visit(
        "max_roll_pitch_rate_rad_s", self.max_roll_pitch_rate_rad_s,
        Field("rad/s", "body roll/pitch rate limit of the rate loop").at_least(0.1).at_most(50.0));
    visit("max_yaw_rate_rad_s", self.max_yaw_rate_rad_s,
          Field("rad/s", "body yaw rate limit").at_least(0.1).at_most(50.0));
  }

  static QuadrotorParams load(cover::config::YamlReader& reader);
  // Throws config::ConfigError naming "<context>.<key>".
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

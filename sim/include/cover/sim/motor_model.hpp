#pragma once

#include "cover/config/param_fields.hpp"

namespace cover::sim {

// One motor and its propeller, driven by the firmware's normalised output u in [0, 1]
// (PX4's HIL_ACTUATOR_CONTROLS.controls[i], ArduPilot's (pwm - 1000) / 1000).
//
// The firmware's thrust curve sets the steady thrust: r = (u - spin_min) / (spin_max -
// spin_min) clipped to [0, 1], thrust fraction = (1 - e) r + e r^2 (ArduCopter's
// MOT_SPIN_MIN/MAX and MOT_THST_EXPO; PX4's THR_MDL_FAC with spin range [0, 1]). The rotor
// speed w chases the speed of that thrust through a first-order lag; thrust = k_T w^2 and
// the reaction torque = k_Q w^2, with k_T = max_thrust / max_speed^2, k_Q = ratio * k_T.
struct MotorModelParams {
  double max_thrust_n = 5.0;               // one rotor at u = spin_max
  double max_rotor_speed_rad_s = 1100.0;   // at max_thrust_n (Gazebo iris: 1100 rad/s)
  double torque_to_thrust_ratio_m = 0.05;  // PX4's CA_ROTORi_KM magnitude
  double motor_time_constant_s = 0.02;     // rotor-speed lag, first order
  double spin_min = 0.0;                   // u below which the rotor gives no thrust
  double spin_max = 1.0;                   // u at which it gives max_thrust_n
  double thrust_expo = 0.0;                // e: 0 linear (PX4), 0.65 ArduCopter

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("max_thrust_n", self.max_thrust_n,
          Field("N", "one rotor's thrust at u = spin_max").above(0.0).at_most(200.0));
    visit("max_rotor_speed_rad_s", self.max_rotor_speed_rad_s,
          Field("rad/s", "rotor speed at max_thrust_n (sets k_T = max_thrust / speed^2)")
              .above(10.0)
              .at_most(10000.0));
    visit("torque_to_thrust_ratio_m", self.torque_to_thrust_ratio_m,
          Field("m", "reaction torque per thrust (k_Q / k_T; PX4's CA_ROTORi_KM)")
              .at_least(0.0)
              .at_most(1.0));
    // Resolved by a 1 kHz RK4 step only from 2 ms up.
    visit("motor_time_constant_s", self.motor_time_constant_s,
          Field("s", "first-order rotor-speed lag").at_least(0.002).at_most(1.0));
    visit("spin_min", self.spin_min,
          Field("", "normalised output below which the rotor gives no thrust (MOT_SPIN_MIN)")
              .at_least(0.0)
              .below(1.0));
    visit("spin_max", self.spin_max,
          Field("", "normalised output giving max_thrust_n (MOT_SPIN_MAX), above spin_min")
              .above(0.0)
              .at_most(1.0));
    visit("thrust_expo", self.thrust_expo,
          Field("", "thrust curve expo e: (1 - e) r + e r^2 (THR_MDL_FAC, MOT_THST_EXPO)")
              .at_least(0.0)
              .at_most(1.0));
  }

  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context) const;
};

// The curve and the rotor's steady state, all from the parameters above.
class MotorModel {
 public:
  // `params` must have passed validate().
  explicit MotorModel(const MotorModelParams& params);

  // Steady thrust fraction of max_thrust_n at output u (u clipped to [0, 1]).
  double thrust_fraction(double u) const;
  // The smallest output whose steady thrust fraction is `fraction` (clipped to [0, 1]).
  double output_for_fraction(double fraction) const;
  // The rotor speed the lag chases at output u.
  double target_speed_rad_s(double u) const;
  double thrust_n(double speed_rad_s) const { return k_thrust_ * speed_rad_s * speed_rad_s; }
  // Magnitude of the reaction torque; its sign is the rotor's spin (rotor_geometry.hpp).
  double torque_n_m(double speed_rad_s) const { return k_torque_ * speed_rad_s * speed_rad_s; }
  // d(speed)/dt of the lag.
  double speed_rate_rad_s2(double speed_rad_s, double u) const;

  double thrust_coefficient_n_s2() const { return k_thrust_; }
  double torque_coefficient_n_m_s2() const { return k_torque_; }
  const MotorModelParams& params() const { return params_; }

 private:
  MotorModelParams params_;
  double k_thrust_;
  double k_torque_;
};

}  // namespace cover::sim

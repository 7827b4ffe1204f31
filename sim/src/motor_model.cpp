#include "cover/sim/motor_model.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim {

void MotorModelParams::validate(const std::string& context) const {
  config::check_fields(*this, context);
  config::check(spin_max > spin_min, context + ".spin_max", "must exceed spin_min");
}

MotorModel::MotorModel(const MotorModelParams& params)
    : params_(params),
      k_thrust_(params.max_thrust_n /
                (params.max_rotor_speed_rad_s * params.max_rotor_speed_rad_s)),
      k_torque_(params.torque_to_thrust_ratio_m * k_thrust_) {}

double MotorModel::thrust_fraction(double u) const {
  const double r =
      std::clamp((u - params_.spin_min) / (params_.spin_max - params_.spin_min), 0.0, 1.0);
  const double e = params_.thrust_expo;
  return (1.0 - e) * r + e * r * r;
}

double MotorModel::output_for_fraction(double fraction) const {
  const double f = std::clamp(fraction, 0.0, 1.0);
  const double e = params_.thrust_expo;
  // Root in [0, 1] of e r^2 + (1 - e) r - f = 0; the linear curve needs no root.
  const double r =
      e <= 0.0 ? f : (-(1.0 - e) + std::sqrt((1.0 - e) * (1.0 - e) + 4.0 * e * f)) / (2.0 * e);
  return params_.spin_min + r * (params_.spin_max - params_.spin_min);
}

double MotorModel::target_speed_rad_s(double u) const {
  return params_.max_rotor_speed_rad_s * std::sqrt(thrust_fraction(u));
}

double MotorModel::speed_rate_rad_s2(double speed_rad_s, double u) const {
  return (target_speed_rad_s(u) - speed_rad_s) / params_.motor_time_constant_s;
}

}  // namespace cover::sim

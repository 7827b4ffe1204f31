#include "cover/sim/quadrotor.hpp"

#include <algorithm>
#include <cmath>

namespace cover::sim {

namespace {

// RK4 state: p(3) v(3) q(4: w x y z) w(3) T(1).
using StateVector = Eigen::Matrix<double, 14, 1>;

StateVector pack(const QuadrotorState& s) {
  StateVector x;
  x(0) = s.position_m.x, x(1) = s.position_m.y, x(2) = s.position_m.z;
  x(3) = s.velocity_m_s.x, x(4) = s.velocity_m_s.y, x(5) = s.velocity_m_s.z;
  x(6) = s.attitude.w, x(7) = s.attitude.x, x(8) = s.attitude.y, x(9) = s.attitude.z;
  x(10) = s.body_rate_rad_s.x, x(11) = s.body_rate_rad_s.y, x(12) = s.body_rate_rad_s.z;
  x(13) = s.thrust_n;
  return x;
}

void unpack(const StateVector& x, QuadrotorState& s) {
  s.position_m = Vec3(Eigen::Vector3d(x.segment<3>(0)));
  s.velocity_m_s = Vec3(Eigen::Vector3d(x.segment<3>(3)));
  Eigen::Quaterniond q(x(6), x(7), x(8), x(9));
  q.normalize();  // RK4 drifts off the unit sphere slowly; renormalise each step
  s.attitude = Quat(q);
  s.body_rate_rad_s = Vec3(Eigen::Vector3d(x.segment<3>(10)));
  s.thrust_n = x(13);
}

struct PlantInputs {
  Eigen::Vector3d rate_target_rad_s;
  double thrust_target_n;
  double mass_kg;
  double gravity_m_s2;
};

StateVector derivative(const StateVector& x, const PlantInputs& in, const QuadrotorParams& p) {
  const Eigen::Vector3d v = x.segment<3>(3);
  // Non-normalised inside RK4 stages on purpose: R(q) of a unit-ish q is fine at 1 kHz.
  const Eigen::Quaterniond q(x(6), x(7), x(8), x(9));
  const Eigen::Vector3d rate = x.segment<3>(10);
  const double thrust_n = x(13);
  const Eigen::Matrix3d rotation = q.normalized().toRotationMatrix();

  const Eigen::Vector3d thrust_accel = rotation.col(2) * (thrust_n / in.mass_kg);
  const Eigen::Vector3d drag_accel =
      -rotation * p.drag_coefficients_1_s.cwiseProduct(rotation.transpose() * v);

  // q' = 1/2 q (x) [0, w]
  const Eigen::Quaterniond rate_quat(0.0, rate.x(), rate.y(), rate.z());
  const Eigen::Quaterniond q_dot = q * rate_quat;

  StateVector dx;
  dx.segment<3>(0) = v;
  dx.segment<3>(3) = thrust_accel + drag_accel - Eigen::Vector3d(0, 0, in.gravity_m_s2);
  dx(6) = 0.5 * q_dot.w();
  dx(7) = 0.5 * q_dot.x();
  dx(8) = 0.5 * q_dot.y();
  dx(9) = 0.5 * q_dot.z();
  dx.segment<3>(10) = (in.rate_target_rad_s - rate) / p.rate_time_constant_s;
  dx(13) = (in.thrust_target_n - thrust_n) / p.thrust_time_constant_s;
  return dx;
}

}  // namespace

QuadrotorParams QuadrotorParams::load(cover::config::YamlReader& reader) {
  QuadrotorParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void QuadrotorParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
  cover::config::check(max_thrust_m_s2 > min_thrust_m_s2, context + ".max_thrust_m_s2",
                       "must exceed min_thrust_m_s2");
}

Quadrotor::Quadrotor(const QuadrotorParams& params) : params_(params) {}

QuadrotorCommand Quadrotor::saturate(const QuadrotorCommand& command) const {
  const double rp = params_.max_roll_pitch_rate_rad_s;
  const double yaw = params_.max_yaw_rate_rad_s;
  QuadrotorCommand out;
  out.thrust_m_s2 =
      std::clamp(command.thrust_m_s2, params_.min_thrust_m_s2, params_.max_thrust_m_s2);
  out.body_rate_rad_s = Vec3(std::clamp(command.body_rate_rad_s.x, -rp, rp),
                             std::clamp(command.body_rate_rad_s.y, -rp, rp),
                             std::clamp(command.body_rate_rad_s.z, -yaw, yaw));
  return out;
}

double Quadrotor::hover_thrust_command_m_s2(double extra_mass_kg, double gravity_m_s2) const {
  return gravity_m_s2 * (params_.mass_true_kg + extra_mass_kg) / params_.mass_nominal_kg;
}

void Quadrotor::step(QuadrotorState& state, const QuadrotorCommand& command, double extra_mass_kg,
                     double gravity_m_s2, double dt_s) const {
  const QuadrotorCommand limited = saturate(command);
  const PlantInputs inputs{limited.body_rate_rad_s.eigen(),
                           limited.thrust_m_s2 * params_.mass_nominal_kg,
                           params_.mass_true_kg + extra_mass_kg, gravity_m_s2};
  const StateVector x = pack(state);
  const StateVector k1 = derivative(x, inputs, params_);
  const StateVector k2 = derivative(x + 0.5 * dt_s * k1, inputs, params_);
  const StateVector k3 = derivative(x + 0.5 * dt_s * k2, inputs, params_);
  const StateVector k4 = derivative(x + dt_s * k3, inputs, params_);
  unpack(x + dt_s / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4), state);
}

}  // namespace cover::sim

#include "cover/sim/motor_quadrotor.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace cover::sim {

namespace {

// RK4 state: p(3) v(3) q(4: w x y z) w(3) rotor speeds(4).
using StateVector = Eigen::Matrix<double, 17, 1>;

StateVector pack(const MotorQuadrotorState& s) {
  StateVector x;
  x.segment<3>(0) = s.body.position_m.eigen();
  x.segment<3>(3) = s.body.velocity_m_s.eigen();
  x(6) = s.body.attitude.w, x(7) = s.body.attitude.x, x(8) = s.body.attitude.y,
  x(9) = s.body.attitude.z;
  x.segment<3>(10) = s.body.body_rate_rad_s.eigen();
  for (int i = 0; i < kRotorCount; ++i) x(13 + i) = s.rotor_speed_rad_s[i];
  return x;
}

MotorQuadrotorState unpack(const StateVector& x) {
  MotorQuadrotorState s;
  s.body.position_m = Vec3(Eigen::Vector3d(x.segment<3>(0)));
  s.body.velocity_m_s = Vec3(Eigen::Vector3d(x.segment<3>(3)));
  // Inside RK4 stages q is unit-ish; the rotation below normalises it.
  s.body.attitude = Quat(Eigen::Quaterniond(x(6), x(7), x(8), x(9)));
  s.body.body_rate_rad_s = Vec3(Eigen::Vector3d(x.segment<3>(10)));
  for (int i = 0; i < kRotorCount; ++i) s.rotor_speed_rad_s[i] = x(13 + i);
  return s;
}

double sanitized(double output) {
  return std::isfinite(output) ? std::clamp(output, 0.0, 1.0) : 0.0;
}

}  // namespace

RotorLayout MotorQuadrotorParams::px4_iris_rotors() {
  RotorLayout layout;
  layout[0] = {Eigen::Vector3d(0.1515, -0.245, 0.0), "ccw"};   // front right
  layout[1] = {Eigen::Vector3d(-0.1515, 0.1875, 0.0), "ccw"};  // rear left
  layout[2] = {Eigen::Vector3d(0.1515, 0.245, 0.0), "cw"};     // front left
  layout[3] = {Eigen::Vector3d(-0.1515, -0.1875, 0.0), "cw"};  // rear right
  return layout;
}

void MotorQuadrotorParams::validate(const std::string& context) const {
  config::check_fields(*this, context);
  motor.validate(context + ".motor");
  validate_rotor_layout(rotors, context + ".motor_1..motor_4");
  // Standard gravity: a vehicle that cannot lift its own weight anywhere on Earth.
  config::check(kRotorCount * motor.max_thrust_n > mass_kg * 9.80665,
                context + ".motor.max_thrust_n",
                "times 4 must exceed the weight mass_kg * g (the vehicle could not hover)");
  // A tensor that is not positive definite is not a rigid body's.
  const Eigen::Matrix3d inertia = inertia_kg_m2();
  const Eigen::Vector3d eigenvalues = inertia.selfadjointView<Eigen::Lower>().eigenvalues();
  config::check(eigenvalues.minCoeff() > 0.0, context + ".inertia_products_kg_m2",
                "make the inertia tensor not positive definite");
}

Eigen::Matrix3d MotorQuadrotorParams::inertia_kg_m2() const {
  const Eigen::Vector3d& d = inertia_diagonal_kg_m2;
  const Eigen::Vector3d& p = inertia_products_kg_m2;
  Eigen::Matrix3d j;
  j << d.x(), p.x(), p.y(),  //
      p.x(), d.y(), p.z(),   //
      p.y(), p.z(), d.z();
  return j;
}

MotorQuadrotor::MotorQuadrotor(const MotorQuadrotorParams& params)
    : params_(params),
      motor_(params.motor),
      inertia_(params.inertia_kg_m2()),
      inertia_inverse_(inertia_.inverse()) {}

BodyWrench MotorQuadrotor::wrench(const MotorQuadrotorState& state) const {
  std::array<double, kRotorCount> thrust{};
  std::array<double, kRotorCount> torque{};
  for (int i = 0; i < kRotorCount; ++i) {
    thrust[i] = motor_.thrust_n(state.rotor_speed_rad_s[i]);
    torque[i] = motor_.torque_n_m(state.rotor_speed_rad_s[i]);
  }
  return rotor_wrench(params_.rotors, thrust, torque);
}

Eigen::Vector3d MotorQuadrotor::linear_acceleration_m_s2(const MotorQuadrotorState& state,
                                                         double extra_mass_kg,
                                                         double gravity_m_s2) const {
  const Eigen::Matrix3d rotation = state.body.attitude.eigen().normalized().toRotationMatrix();
  const Eigen::Vector3d v = state.body.velocity_m_s.eigen();
  const double mass_kg = params_.mass_kg + extra_mass_kg;
  const Eigen::Vector3d thrust_accel = rotation * wrench(state).force_n / mass_kg;
  const Eigen::Vector3d drag_accel =
      -rotation * params_.drag_coefficients_1_s.cwiseProduct(rotation.transpose() * v);
  return thrust_accel + drag_accel - Eigen::Vector3d(0.0, 0.0, gravity_m_s2);
}

Eigen::Vector3d MotorQuadrotor::angular_acceleration_rad_s2(
    const MotorQuadrotorState& state) const {
  const Eigen::Vector3d w = state.body.body_rate_rad_s.eigen();
  return inertia_inverse_ * (wrench(state).torque_n_m - w.cross(inertia_ * w));
}

void MotorQuadrotor::step(MotorQuadrotorState& state, const MotorOutputs& outputs,
                          double extra_mass_kg, double gravity_m_s2, double dt_s) const {
  MotorOutputs u{};
  for (int i = 0; i < kRotorCount; ++i) u[i] = sanitized(outputs[i]);

  const auto derivative = [&](const StateVector& x) {
    const MotorQuadrotorState s = unpack(x);
    const Eigen::Quaterniond q(x(6), x(7), x(8), x(9));
    const Eigen::Vector3d w = x.segment<3>(10);
    const Eigen::Quaterniond q_dot = q * Eigen::Quaterniond(0.0, w.x(), w.y(), w.z());
    StateVector dx;
    dx.segment<3>(0) = x.segment<3>(3);
    dx.segment<3>(3) = linear_acceleration_m_s2(s, extra_mass_kg, gravity_m_s2);
    dx(6) = 0.5 * q_dot.w();
    dx(7) = 0.5 * q_dot.x();
    dx(8) = 0.5 * q_dot.y();
    dx(9) = 0.5 * q_dot.z();
    dx.segment<3>(10) = angular_acceleration_rad_s2(s);
    for (int i = 0; i < kRotorCount; ++i) {
      dx(13 + i) = motor_.speed_rate_rad_s2(x(13 + i), u[i]);
    }
    return dx;
  };

  const StateVector x = pack(state);
  const StateVector k1 = derivative(x);
  const StateVector k2 = derivative(x + 0.5 * dt_s * k1);
  const StateVector k3 = derivative(x + 0.5 * dt_s * k2);
  const StateVector k4 = derivative(x + dt_s * k3);
  state = unpack(x + dt_s / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4));
  state.body.attitude = Quat(state.body.attitude.eigen().normalized());  // RK4 drifts slowly
  state.body.thrust_n = wrench(state).force_n.z();
}

std::array<double, kRotorCount> MotorQuadrotor::steady_rotor_speeds(
    const MotorOutputs& outputs) const {
  std::array<double, kRotorCount> speeds{};
  for (int i = 0; i < kRotorCount; ++i)
    speeds[i] = motor_.target_speed_rad_s(sanitized(outputs[i]));
  return speeds;
}

double MotorQuadrotor::hover_output(double extra_mass_kg, double gravity_m_s2) const {
  const double weight_n = (params_.mass_kg + extra_mass_kg) * gravity_m_s2;
  return motor_.output_for_fraction(weight_n / (kRotorCount * params_.motor.max_thrust_n));
}

}  // namespace cover::sim

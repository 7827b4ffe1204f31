#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/motor_model.hpp"
#include "cover/sim/rotor_geometry.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::sim {

// The motor-level quadrotor a real firmware flies (beside quadrotor.hpp's rate model,
// which takes body rates and thrust): four rotors (motor_model.hpp, rotor_geometry.hpp)
// on a rigid body with a full inertia tensor and linear drag. World ENU, body FLU.
//
// The defaults are PX4's SITL iris (10016_none_iris: rotor positions, CA_ROTORi_KM, motor
// numbering; the Gazebo iris's rotor speed and inertia shape) sized to COVER's vehicle:
// 1.05 kg true mass, 4 x 5 N = 20 N maximum thrust (world_default.yaml: max_thrust_m_s2 20
// per 1.0 kg nominal), inertia the iris's scaled by 1.05 / 1.5. Linear thrust curve, as
// PX4 assumes (THR_MDL_FAC 0): hover at u = 1.05 * 9.81 / 20 = 0.515.
struct MotorQuadrotorParams {
  double mass_kg = 1.05;
  Eigen::Vector3d inertia_diagonal_kg_m2 = Eigen::Vector3d(0.0203875, 0.0203875, 0.0386575);
  Eigen::Vector3d inertia_products_kg_m2 = Eigen::Vector3d::Zero();  // Ixy, Ixz, Iyz
  Eigen::Vector3d drag_coefficients_1_s = Eigen::Vector3d(0.3, 0.3, 0.1);
  MotorModelParams motor;
  RotorLayout rotors = px4_iris_rotors();

  // PX4 10016_none_iris, CA_ROTOR0..3 (FRD x, y -> FLU x, -y).
  static RotorLayout px4_iris_rotors();

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("mass_kg", self.mass_kg,
          Field("kg", "the vehicle's true mass (without payload)").at_least(0.01).at_most(100.0));
    visit("inertia_diagonal_kg_m2", self.inertia_diagonal_kg_m2,
          Field("kg m^2", "Ixx, Iyy, Izz about the centre of mass, body FLU")
              .above(0.0)
              .at_most(100.0));
    visit("inertia_products_kg_m2", self.inertia_products_kg_m2,
          Field("kg m^2", "products of inertia Ixy, Ixz, Iyz (tensor entries, body FLU)")
              .at_least(-100.0)
              .at_most(100.0));
    visit("drag_coefficients_1_s", self.drag_coefficients_1_s,
          Field("1/s", "linear drag per unit mass in body x, y, z").at_least(0.0).at_most(10.0));
    visit("motor", self.motor, Field("", "every motor's curve, lag and coefficients"));
    visit("motor_1", self.rotors[0], Field("", "the rotor on the firmware's output 1"));
    visit("motor_2", self.rotors[1], Field("", "the rotor on output 2"));
    visit("motor_3", self.rotors[2], Field("", "the rotor on output 3"));
    visit("motor_4", self.rotors[3], Field("", "the rotor on output 4"));
  }

  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context = "motor_quadrotor") const;

  Eigen::Matrix3d inertia_kg_m2() const;
};

// The plant's state: the rigid body (thrust_n is the rotors' summed thrust) and each
// rotor's speed, in output order.
struct MotorQuadrotorState {
  QuadrotorState body;
  std::array<double, kRotorCount> rotor_speed_rad_s{};
};

// Normalised outputs in [0, 1], in the firmware's output order.
using MotorOutputs = std::array<double, kRotorCount>;

class MotorQuadrotor {
 public:
  // `params` must have passed validate().
  explicit MotorQuadrotor(const MotorQuadrotorParams& params);

  // One RK4 step of length dt_s in free flight with `outputs` held (clipped to [0, 1]; a
  // non-finite output counts as 0, a motor stopped). `extra_mass_kg` is a payload. Contact
  // is the caller's (surface_contact.hpp), after the step, as for the rate model.
  void step(MotorQuadrotorState& state, const MotorOutputs& outputs, double extra_mass_kg,
            double gravity_m_s2, double dt_s) const;

  // The rotors' wrench on the body at the state's rotor speeds.
  BodyWrench wrench(const MotorQuadrotorState& state) const;
  // World-frame acceleration of the centre of mass (thrust, drag, gravity).
  Eigen::Vector3d linear_acceleration_m_s2(const MotorQuadrotorState& state, double extra_mass_kg,
                                           double gravity_m_s2) const;
  // Body-frame angular acceleration: J^-1 (torque - w x J w).
  Eigen::Vector3d angular_acceleration_rad_s2(const MotorQuadrotorState& state) const;

  // The rotor speeds `outputs` settle at (a vehicle spun up before a test or a mid-air start).
  std::array<double, kRotorCount> steady_rotor_speeds(const MotorOutputs& outputs) const;
  // The output (the same on every motor) that holds the vehicle in hover.
  double hover_output(double extra_mass_kg, double gravity_m_s2) const;

  const MotorModel& motor() const { return motor_; }
  const MotorQuadrotorParams& params() const { return params_; }

 private:
  MotorQuadrotorParams params_;
  MotorModel motor_;
  Eigen::Matrix3d inertia_;
  Eigen::Matrix3d inertia_inverse_;
};

}  // namespace cover::sim

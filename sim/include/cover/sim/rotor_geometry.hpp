#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "cover/config/param_fields.hpp"

namespace cover::sim {

constexpr int kRotorCount = 4;

// One rotor of the airframe: where it sits in the body frame (FLU) and which way it turns
// seen from above. Its thrust acts along body +z; a rotor turning counter-clockwise pushes
// the body clockwise (reaction torque along body -z), as PX4's CA_ROTORi_KM > 0 (CCW)
// and ArduCopter's motor table state.
struct RotorParams {
  Eigen::Vector3d position_flu_m = Eigen::Vector3d::Zero();
  std::string spin = "ccw";

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("position_flu_m", self.position_flu_m,
          Field("m", "rotor hub in the body frame: x forward, y left, z up")
              .at_least(-5.0)
              .at_most(5.0));
    visit("spin", self.spin, Field("", "turning direction seen from above").one_of({"ccw", "cw"}));
  }

  // +1 counter-clockwise, -1 clockwise (seen from above).
  double spin_sign() const { return spin == "ccw" ? 1.0 : -1.0; }
};

// Rotors in the firmware's output order: rotors[i] is driven by output i + 1 (PX4's
// HIL_ACTUATOR_CONTROLS.controls[i], ArduPilot's SERVO(i + 1)).
using RotorLayout = std::array<RotorParams, kRotorCount>;

struct BodyWrench {
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero();     // body FLU
  Eigen::Vector3d torque_n_m = Eigen::Vector3d::Zero();  // body FLU, about the centre of mass
};

// The rotors' force and torque on the body: sum of thrust_i e_z, sum of
// p_i x (thrust_i e_z) - spin_i reaction_i e_z.
BodyWrench rotor_wrench(const RotorLayout& layout, const std::array<double, kRotorCount>& thrust_n,
                        const std::array<double, kRotorCount>& reaction_torque_n_m);

// Throws config::ConfigError naming "<context>..." unless two rotors turn each way (the
// airframe could not yaw, or would spin at hover, otherwise).
void validate_rotor_layout(const RotorLayout& layout, const std::string& context);

}  // namespace cover::sim

#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "cover/config/param_fields.hpp"
#include "cover/sim/sensor_rate_field.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::sim {

// A magnetometer in a constant world field: the field rotated into body FLU, with white
// noise and a constant bias (hard iron) drawn once from the seed.
struct MagnetometerParams {
  double rate_hz = 100.0;  // Gazebo iris's magnetometer_plugin pubRate
  // Zurich (PX4 SITL's default home), WMM: 0.009 G east, 0.216 G north, 0.426 G down.
  Eigen::Vector3d world_field_enu_gauss = Eigen::Vector3d(0.009, 0.216, -0.426);
  double noise_gauss = 0.002;
  double bias_sigma_gauss = 0.005;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate (Gazebo iris: 100); must divide the physics rate"));
    visit("world_field_enu_gauss", self.world_field_enu_gauss,
          Field("G", "Earth's field in the world frame: east, north, up")
              .at_least(-1.0)
              .at_most(1.0));
    visit("noise_gauss", self.noise_gauss,
          Field("G", "white noise 1-sigma per axis").at_least(0.0).at_most(0.5));
    visit("bias_sigma_gauss", self.bias_sigma_gauss,
          Field("G", "1-sigma of the constant bias per axis").at_least(0.0).at_most(0.5));
  }
};

struct MagnetometerSample {
  double stamp_s = 0.0;
  Eigen::Vector3d field_flu_gauss = Eigen::Vector3d::Zero();
};

class Magnetometer {
 public:
  Magnetometer(const MagnetometerParams& params, std::uint64_t seed);
  MagnetometerSample sample(const QuadrotorState& body, double stamp_s);

  const Eigen::Vector3d& bias_gauss() const { return bias_gauss_; }

 private:
  Eigen::Vector3d white_noise(double sigma);

  MagnetometerParams params_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  Eigen::Vector3d bias_gauss_;
};

}  // namespace cover::sim

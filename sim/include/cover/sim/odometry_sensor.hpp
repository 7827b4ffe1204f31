#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/sensor_rate_field.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// Each UGV's wheel odometry (on the UGVs whose has_wheel_odometry is set): the signed
// forward speed along G_k's x axis, times a wheel-radius scale error drawn once per UGV,
// plus white noise. Sampled on IMU samples (the device read delivers both together).
struct OdometrySensorParams {
  double rate_hz = 50.0;  // must divide the IMU rate
  double speed_noise_m_s = 0.02;
  // 1-sigma of the relative scale error (a wheel radius off by 1 % reads 1 % fast).
  double scale_error_sigma = 0.01;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate; must divide imu.rate_hz (delivered with an IMU sample)"));
    visit("speed_noise_m_s", self.speed_noise_m_s,
          Field("m/s", "white noise 1-sigma").at_least(0.0).at_most(1.0));
    visit("scale_error_sigma", self.scale_error_sigma,
          Field("", "1-sigma of the per-UGV relative scale error (wheel radius)")
              .at_least(0.0)
              .at_most(0.2));
  }

  static OdometrySensorParams load(cover::config::YamlReader& reader);
  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context = "odometry") const;
};

// Noise-free forward speed of a planar UGV: its world velocity along its heading.
double true_forward_speed_m_s(const UgvState& ugv);

class OdometrySensor {
 public:
  // `has_odometry[k]`: UGV k has wheel encoders (entries beyond the vector: none).
  OdometrySensor(const OdometrySensorParams& params, double physics_rate_hz,
                 const std::vector<bool>& has_odometry, std::uint64_t seed);

  // Call after every physics step; samples every equipped UGV at the sensor rate.
  void update(const WorldState& world);

  // UGV k's wheel speed sampled on the latest update() step, if it was due and k has
  // odometry; nothing otherwise.
  std::optional<double> sampled_now(int ugv_index) const { return now_[ugv_index]; }
  bool has_odometry(int ugv_index) const { return ugvs_[ugv_index].equipped; }

 private:
  struct UgvOdometry {
    bool equipped = false;
    std::mt19937_64 rng;
    std::normal_distribution<double> unit_normal{0.0, 1.0};
    double scale = 1.0;
  };

  OdometrySensorParams params_;
  std::uint64_t sample_period_steps_;
  std::array<UgvOdometry, kMaxUgvs> ugvs_;
  std::array<std::optional<double>, kMaxUgvs> now_{};
};

}  // namespace cover::sim

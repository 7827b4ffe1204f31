#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <deque>
#include <random>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/sensor_rate_field.hpp"
#include "cover/vocabulary/relative_state.hpp"
#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

// Motion-capture-like relative state of the UAV in every UGV frame (the paper used
// NOKOV mocap indoors): small white noise, a fixed latency, a fixed rate.
struct RelativeSensorParams {
  double rate_hz = 100.0;             // must divide the physics rate
  double latency_s = 0.01;            // quantised to the physics step
  double position_noise_m = 0.001;    // 1-sigma, per axis
  double velocity_noise_m_s = 0.01;   // 1-sigma, per axis
  double attitude_noise_rad = 0.003;  // 1-sigma, per axis of a small rotation
  // Probability that a sample is lost (mocap occlusion, Wi-Fi loss): consumers then see
  // an older stamp. 0 by default; raise it to test the controller's staleness handling.
  double dropout_probability = 0.0;

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate; must divide world.physics_rate_hz"));
    visit("latency_s", self.latency_s,
          Field("s", "delay from sampling to availability, rounded to the physics step")
              .at_least(0.0)
              .at_most(1.0));
    visit("position_noise_m", self.position_noise_m,
          Field("m", "white noise 1-sigma per axis").at_least(0.0).at_most(1.0));
    visit("velocity_noise_m_s", self.velocity_noise_m_s,
          Field("m/s", "white noise 1-sigma per axis").at_least(0.0).at_most(5.0));
    visit("attitude_noise_rad", self.attitude_noise_rad,
          Field("rad", "small-rotation noise 1-sigma per axis").at_least(0.0).at_most(0.5));
    visit("dropout_probability", self.dropout_probability,
          Field("", "probability that a sample is lost (occlusion, radio loss)")
              .at_least(0.0)
              .at_most(1.0));
  }

  static RelativeSensorParams load(cover::config::YamlReader& reader);
  // Throws config::ConfigError naming "<context>.<key>".
  void validate(const std::string& context = "relative_sensor") const;
};

// The UAV state in G_k, as the controller consumes it (one struct for the sensor, the
// controller and the wire conversions).
using RelativeState = model::RelativeState;

RelativeState true_relative_state(const QuadrotorState& uav, const UgvState& ugv, double stamp_s);

class RelativeSensor {
 public:
  // `params` must have passed validate(); the rates were checked by WorldParams.
  RelativeSensor(const RelativeSensorParams& params, double physics_rate_hz, int ugv_count,
                 std::uint64_t seed);

  // Call after every physics step: samples at the sensor rate, releases after the latency.
  void update(const WorldState& world);

  bool has_measurement() const { return has_measurement_; }
  // The newest measurement of the UAV in G_k whose latency has elapsed
  // (0 <= ugv_index < ugv count; meaningful once has_measurement()).
  const RelativeState& latest(int ugv_index) const { return latest_[ugv_index]; }
  double latency_s() const { return latency_steps_ * physics_dt_s_; }

 private:
  struct Pending {
    std::uint64_t release_step;
    std::array<RelativeState, kMaxUgvs> states;
  };
  RelativeState add_noise(const RelativeState& truth);

  RelativeSensorParams params_;
  double physics_dt_s_;
  std::uint64_t sample_period_steps_;
  std::uint64_t latency_steps_;
  int ugv_count_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  std::uniform_real_distribution<double> unit_uniform_{0.0, 1.0};
  std::deque<Pending> pending_;
  std::array<RelativeState, kMaxUgvs> latest_{};
  bool has_measurement_ = false;
};

}  // namespace cover::sim

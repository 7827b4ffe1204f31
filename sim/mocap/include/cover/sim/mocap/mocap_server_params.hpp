#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"

namespace cover::sim::mocap {

// The simulated motion-capture system (config/sim/mocap.yaml, section `mocap`): what
// cover-sim --mocap vrpn serves.
struct MocapServerParams {
  double rate_hz = 100.0;             // frames per second; the control rate must be a multiple
  double latency_s = 0.01;            // capture to send, quantised to the control period
  double position_noise_m = 0.0005;   // 1-sigma per axis (a good mocap: sub-millimetre)
  double attitude_noise_rad = 0.002;  // 1-sigma per axis of a small rotation
  double dropout_probability = 0.01;  // per body and frame: the body is missing
  std::string up_axis = "z";          // z or y (OptiTrack Motive's default)
  std::string units = "m";            // m or mm
  std::string uav_prefix = "uav";     // body names: uav0, uav1, ...
  std::string ugv_prefix = "ugv";     // ugv0, ugv1, ...
  std::uint64_t seed = 1;             // noise and dropouts

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          Field("Hz", "frames per second; the control rate must be a multiple")
              .at_least(1.0)
              .at_most(1000.0));
    visit(
        "latency_s", self.latency_s,
        Field("s", "capture to send, quantised to the control period").at_least(0.0).at_most(0.5));
    visit("position_noise_m", self.position_noise_m,
          Field("m", "white noise 1-sigma per axis").at_least(0.0).at_most(0.1));
    visit("attitude_noise_rad", self.attitude_noise_rad,
          Field("rad", "white noise 1-sigma per axis of a small rotation")
              .at_least(0.0)
              .at_most(0.2));
    visit("dropout_probability", self.dropout_probability,
          Field("", "per body and frame: the body is missing (occlusion)")
              .at_least(0.0)
              .at_most(0.5));
    visit("up_axis", self.up_axis,
          Field("", "the server's up axis (OptiTrack Motive's default: y)").one_of({"z", "y"}));
    visit("units", self.units, Field("", "the server's units").one_of({"m", "mm"}));
    visit("uav_prefix", self.uav_prefix,
          Field("", "UAV body names: <prefix>0, <prefix>1, ...; not empty, not ugv_prefix"));
    visit("ugv_prefix", self.ugv_prefix, Field("", "UGV body names: <prefix>0, ...; not empty"));
    visit("seed", self.seed, Field("", "seed of the noise and dropouts"));
  }

  static MocapServerParams load_file(const std::string& path);
  static MocapServerParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim::mocap

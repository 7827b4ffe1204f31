#pragma once

#include <cstdint>
#include <string>

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

  static MocapServerParams load_file(const std::string& path);
  static MocapServerParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::sim::mocap

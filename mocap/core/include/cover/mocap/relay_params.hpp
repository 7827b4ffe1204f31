#pragma once

#include <string>
#include <vector>

#include "cover/config/yaml_reader.hpp"

namespace cover::mocap {

// One rigid body the relay reads: which vehicle, and its name on the server.
struct BodyBinding {
  enum class Vehicle { Uav, Ugv };
  Vehicle vehicle = Vehicle::Uav;
  int id = 0;        // u or k
  std::string name;  // the server's tracker name ("UAV_A")
  std::string key() const { return (vehicle == Vehicle::Uav ? "uav" : "ugv") + std::to_string(id); }
};

// The per-body constant-velocity Kalman filter (docs/mocap.md: method and delay).
struct FilterParams {
  double accel_noise_m_s2 = 8.0;       // 1-sigma white acceleration of a body, per axis
  double position_noise_m = 0.001;     // 1-sigma of a mocap position, per axis
  double yaw_jerk_noise_rad_s3 = 1.0;  // yaw: constant-acceleration model
  double yaw_noise_rad = 0.004;
};

// cover-mocap-relay's settings (config/mocap.yaml, section `mocap`). Only `server` and
// `bodies` are required.
struct RelayParams {
  std::string server;               // "HOST:PORT" (port 3883 when left out)
  std::string up_axis = "z";        // the server's up axis: z or y
  std::string units = "m";          // the server's units: m or mm
  std::vector<BodyBinding> bodies;  // from `bodies: {uav0: "UAV_A", ugv1: "Truck_2"}`
  FilterParams filter;
  // A measurement this far (m) from the filter's prediction is a jump: rejected, the body's
  // pairs invalid until it comes back near, or until the jump has lasted jump_reset_s (then
  // the filter starts again at the new place).
  double jump_gate_m = 0.25;
  double jump_reset_s = 0.2;
  // No accepted measurement of a body for this long: its pairs are invalid (the filter
  // coasts through shorter gaps, e.g. one dropped frame).
  double lost_after_s = 0.05;
  // Updates after a (re)start before a body counts (its velocity needs a few).
  int warmup_updates = 3;
  // A frame whose bodies have not all arrived is used this long (wall clock) after its
  // first message, s.
  double frame_timeout_s = 0.003;
  // How a server time becomes ours: "server" (the same clock: the simulator, or hosts
  // synchronised by chrony), "offset" (our arrival time minus the smallest delay seen).
  std::string time_source = "offset";
  double offset_window_s = 10.0;
  // The TCP link.
  double connect_timeout_s = 1.0;
  double backoff_min_s = 0.1;
  double backoff_max_s = 2.0;
  double silence_timeout_s = 1.0;

  static RelayParams load_file(const std::string& path);
  static RelayParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
  std::vector<int> uav_ids() const;
  std::vector<int> ugv_ids() const;
};

}  // namespace cover::mocap

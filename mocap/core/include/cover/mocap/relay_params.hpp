#pragma once

#include <string>
#include <vector>

#include "cover/config/param_fields.hpp"
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

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("accel_noise_m_s2", self.accel_noise_m_s2,
          Field("m/s^2", "1-sigma white acceleration of a body, per axis: what the vehicles can do")
              .at_least(1e-3)
              .at_most(1e3));
    visit("position_noise_m", self.position_noise_m,
          Field("m", "1-sigma of a mocap position, per axis").at_least(1e-6).at_most(1.0));
    visit("yaw_jerk_noise_rad_s3", self.yaw_jerk_noise_rad_s3,
          Field("rad/s^3", "yaw: constant-acceleration model").at_least(1e-3).at_most(1e4));
    visit("yaw_noise_rad", self.yaw_noise_rad,
          Field("rad", "1-sigma of a mocap yaw").at_least(1e-6).at_most(1.0));
  }
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

  // Each field once (config/param_fields.hpp), but for `bodies` (a map of any uav<u> /
  // ugv<k> keys) that from_yaml reads itself.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("server", self.server,
          Field("", "the VRPN server, HOST:PORT (3883 when the port is left out)").required());
    visit("up_axis", self.up_axis,
          Field("", "the server's up axis (Vicon, NOKOV: z; OptiTrack Motive: y)")
              .one_of({"z", "y"}));
    visit("units", self.units, Field("", "the server's units").one_of({"m", "mm"}));
    visit("filter", self.filter, Field("", "per-body constant-velocity Kalman filter"));
    visit("jump_gate_m", self.jump_gate_m,
          Field("m", "a measurement this far from the prediction is a jump: rejected")
              .at_least(0.001)
              .at_most(100.0));
    visit("jump_reset_s", self.jump_reset_s,
          Field("s", "a jump lasting this long restarts the filter at the new place")
              .at_least(0.0)
              .at_most(10.0));
    visit("lost_after_s", self.lost_after_s,
          Field("s", "no accepted measurement this long: the body's pairs are invalid")
              .at_least(0.001)
              .at_most(5.0));
    visit("warmup_updates", self.warmup_updates,
          Field("", "measurements after a (re)start before a body counts")
              .at_least(2.0)
              .at_most(100.0));
    visit("frame_timeout_s", self.frame_timeout_s,
          Field("s", "a frame missing bodies is used this long after its first message")
              .at_least(0.0)
              .at_most(0.1));
    visit("time_source", self.time_source,
          Field("",
                "server: capture times on our clock; offset: ours = server + the smallest "
                "(arrival - capture) over offset_window_s")
              .one_of({"server", "offset"}));
    visit("offset_window_s", self.offset_window_s,
          Field("s", "window of the smallest delay (time_source offset)")
              .at_least(0.1)
              .at_most(3600.0));
    visit("connect_timeout_s", self.connect_timeout_s,
          Field("s", "TCP connect timeout").at_least(0.01).at_most(60.0));
    visit("backoff_min_s", self.backoff_min_s,
          Field("s", "first wait between connection attempts (doubling)")
              .at_least(0.01)
              .at_most(60.0));
    visit("backoff_max_s", self.backoff_max_s,
          Field("s", "longest wait between attempts, >= backoff_min_s")
              .at_least(0.01)
              .at_most(600.0));
    visit(
        "silence_timeout_s", self.silence_timeout_s,
        Field("s", "a connection silent this long is taken as dead").at_least(0.05).at_most(60.0));
  }

  static RelayParams load_file(const std::string& path);
  static RelayParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
  std::vector<int> uav_ids() const;
  std::vector<int> ugv_ids() const;
};

}  // namespace cover::mocap

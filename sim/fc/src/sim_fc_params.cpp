#include "cover/sim/fc/sim_fc_params.hpp"

namespace cover::sim::fc {

using config::check;

// Measured on PX4 SITL's onboard link (docs/autopilots.md, measured on real SITL, 2026-12-04): ATTITUDE 98-100,
// ATTITUDE_QUATERNION 49.8, HIGHRES_IMU 49.8, ATTITUDE_TARGET 10, EXTENDED_SYS_STATE 5,
// SYS_STATUS 5, BATTERY_STATUS 0.5-0.6, ESTIMATOR_STATUS 1, HEARTBEAT 1, ALTITUDE and
// VFR_HUD 10 Hz.
StreamRates StreamRates::px4_onboard() {
  StreamRates r;
  r.heartbeat_hz = 1.0;
  r.highres_imu_hz = 50.0;
  r.attitude_quaternion_hz = 50.0;
  r.attitude_hz = 100.0;
  r.attitude_target_hz = 10.0;
  r.extended_sys_state_hz = 5.0;
  r.sys_status_hz = 5.0;
  r.battery_status_hz = 0.5;
  r.estimator_hz = 1.0;
  r.codec_unknown_hz = 10.0;
  return r;
}

SimFcParams SimFcParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SimFcParams SimFcParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sim_fc", true);
  SimFcParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

void SimFcParams::validate() const {
  config::check_fields(*this, "sim_fc");
  const bool overlap =
      ugv_system_id_base <= system_id_base + 3 && system_id_base <= ugv_system_id_base + 7;
  check(!overlap, "sim_fc.ugv_system_id_base", "must not overlap the UAVs' system ids");
  // Both firmwares send HEARTBEAT whatever else they stream (a bridge finds them by it).
  check(px4.streams.heartbeat_hz > 0.0, "sim_fc.px4.streams.heartbeat_hz",
        "must be > 0 (an autopilot always sends HEARTBEAT)");
  check(ardupilot.streams.heartbeat_hz > 0.0, "sim_fc.ardupilot.streams.heartbeat_hz",
        "must be > 0 (an autopilot always sends HEARTBEAT)");
  check(battery.cell_full_v > battery.cell_empty_v, "sim_fc.battery.cell_full_v",
        "must exceed cell_empty_v");
}

}  // namespace cover::sim::fc

#include "cover/sim/fc/sim_fc_params.hpp"

#include <cmath>

namespace cover::sim::fc {

namespace {

using config::check;

BatteryParams load_battery(config::YamlReader& reader) {
  BatteryParams p;
  reader.optional("cells", p.cells);
  reader.optional("capacity_mah", p.capacity_mah);
  reader.optional("cell_full_v", p.cell_full_v);
  reader.optional("cell_empty_v", p.cell_empty_v);
  reader.optional("hover_current_a", p.hover_current_a);
  reader.optional("idle_current_a", p.idle_current_a);
  reader.optional("internal_resistance_ohm", p.internal_resistance_ohm);
  reader.reject_unknown_keys();
  return p;
}

bool in_range(double value, double low, double high) {
  return std::isfinite(value) && value >= low && value <= high;
}

void validate_battery(const BatteryParams& b) {
  check(b.cells >= 1 && b.cells <= 10, "sim_fc.battery.cells", "must be in [1, 10]");
  check(in_range(b.capacity_mah, 1.0, 1e6), "sim_fc.battery.capacity_mah", "must be in [1, 1e6]");
  check(in_range(b.cell_empty_v, 2.0, 5.0), "sim_fc.battery.cell_empty_v", "must be in [2, 5] V");
  check(in_range(b.cell_full_v, b.cell_empty_v, 5.0) && b.cell_full_v > b.cell_empty_v,
        "sim_fc.battery.cell_full_v", "must exceed cell_empty_v and be <= 5 V");
  check(in_range(b.hover_current_a, 0.0, 500.0), "sim_fc.battery.hover_current_a",
        "must be in [0, 500] A");
  check(in_range(b.idle_current_a, 0.0, 50.0), "sim_fc.battery.idle_current_a",
        "must be in [0, 50] A");
  check(in_range(b.internal_resistance_ohm, 0.0, 1.0), "sim_fc.battery.internal_resistance_ohm",
        "must be in [0, 1] ohm");
}

}  // namespace

SimFcParams SimFcParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SimFcParams SimFcParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sim_fc", true);
  SimFcParams p;
  reader.optional("system_id_base", p.system_id_base);
  reader.optional("ugv_system_id_base", p.ugv_system_id_base);
  reader.optional("heartbeat_rate_hz", p.heartbeat_rate_hz);
  reader.optional("attitude_rate_hz", p.attitude_rate_hz);
  reader.optional("highres_imu_rate_hz", p.highres_imu_rate_hz);
  reader.optional("attitude_target_rate_hz", p.attitude_target_rate_hz);
  reader.optional("extended_sys_state_rate_hz", p.extended_sys_state_rate_hz);
  reader.optional("sys_status_rate_hz", p.sys_status_rate_hz);
  reader.optional("com_of_loss_t_s", p.com_of_loss_t_s);
  reader.optional("guid_timeout_s", p.guid_timeout_s);
  reader.optional("guid_level_hold_s", p.guid_level_hold_s);
  reader.optional("land_speed_m_s", p.land_speed_m_s);
  reader.optional("offboard_stream_min_rate_hz", p.offboard_stream_min_rate_hz);
  reader.optional("offboard_stream_min_s", p.offboard_stream_min_s);
  auto battery = reader.child("battery");
  p.battery = load_battery(battery);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void SimFcParams::validate() const {
  // System ids 1..250: 0 is broadcast, 251..255 are ground stations and tools by convention.
  check(system_id_base >= 1 && system_id_base + 3 <= 250, "sim_fc.system_id_base",
        "must be in [1, 247] (UAVs 0..3 take system_id_base + u <= 250)");
  check(ugv_system_id_base >= 1 && ugv_system_id_base + 7 <= 250, "sim_fc.ugv_system_id_base",
        "must be in [1, 243] (UGVs 0..7 take ugv_system_id_base + k <= 250)");
  const bool overlap =
      ugv_system_id_base <= system_id_base + 3 && system_id_base <= ugv_system_id_base + 7;
  check(!overlap, "sim_fc.ugv_system_id_base", "must not overlap the UAVs' system ids");
  for (const auto& [key, rate] :
       {std::pair<const char*, double>{"heartbeat_rate_hz", heartbeat_rate_hz},
        {"attitude_rate_hz", attitude_rate_hz},
        {"highres_imu_rate_hz", highres_imu_rate_hz},
        {"attitude_target_rate_hz", attitude_target_rate_hz},
        {"extended_sys_state_rate_hz", extended_sys_state_rate_hz},
        {"sys_status_rate_hz", sys_status_rate_hz}}) {
    check(in_range(rate, 0.1, 1000.0), std::string("sim_fc.") + key, "must be in [0.1, 1000] Hz");
  }
  check(in_range(com_of_loss_t_s, 0.01, 60.0), "sim_fc.com_of_loss_t_s", "must be in [0.01, 60] s");
  check(in_range(guid_timeout_s, 0.1, 60.0), "sim_fc.guid_timeout_s", "must be in [0.1, 60] s");
  check(in_range(guid_level_hold_s, 0.0, 600.0), "sim_fc.guid_level_hold_s",
        "must be in [0, 600] s");
  check(in_range(land_speed_m_s, 0.05, 3.0), "sim_fc.land_speed_m_s", "must be in [0.05, 3] m/s");
  check(in_range(offboard_stream_min_rate_hz, 0.1, 100.0), "sim_fc.offboard_stream_min_rate_hz",
        "must be in [0.1, 100] Hz");
  check(in_range(offboard_stream_min_s, 0.0, 10.0), "sim_fc.offboard_stream_min_s",
        "must be in [0, 10] s");
  validate_battery(battery);
}

}  // namespace cover::sim::fc

// config/sim/sim_fc.yaml: the shipped file is the defaults, every key is checked by name.
#include <gtest/gtest.h>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"

namespace {

using cover::sim::fc::SimFcParams;

SimFcParams parse(const std::string& text) {
  return SimFcParams::from_yaml(cover::config::parse_yaml(text, "test.yaml"), "test.yaml");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const cover::config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(SimFcParams, ShippedFileHoldsTheDefaults) {
  const SimFcParams shipped =
      SimFcParams::load_file(cover::config::default_config_dir() + "/sim/sim_fc.yaml");
  const SimFcParams defaults;
  EXPECT_EQ(shipped.system_id_base, defaults.system_id_base);
  EXPECT_EQ(shipped.ugv_system_id_base, defaults.ugv_system_id_base);
  EXPECT_EQ(shipped.heartbeat_rate_hz, defaults.heartbeat_rate_hz);
  EXPECT_EQ(shipped.attitude_rate_hz, defaults.attitude_rate_hz);
  EXPECT_EQ(shipped.highres_imu_rate_hz, defaults.highres_imu_rate_hz);
  EXPECT_EQ(shipped.attitude_target_rate_hz, defaults.attitude_target_rate_hz);
  EXPECT_EQ(shipped.extended_sys_state_rate_hz, defaults.extended_sys_state_rate_hz);
  EXPECT_EQ(shipped.sys_status_rate_hz, defaults.sys_status_rate_hz);
  EXPECT_EQ(shipped.com_of_loss_t_s, defaults.com_of_loss_t_s);
  EXPECT_EQ(shipped.guid_timeout_s, defaults.guid_timeout_s);
  EXPECT_EQ(shipped.guid_level_hold_s, defaults.guid_level_hold_s);
  EXPECT_EQ(shipped.land_speed_m_s, defaults.land_speed_m_s);
  EXPECT_EQ(shipped.offboard_stream_min_rate_hz, defaults.offboard_stream_min_rate_hz);
  EXPECT_EQ(shipped.offboard_stream_min_s, defaults.offboard_stream_min_s);
  EXPECT_EQ(shipped.battery.cells, defaults.battery.cells);
  EXPECT_EQ(shipped.battery.capacity_mah, defaults.battery.capacity_mah);
  EXPECT_EQ(shipped.battery.cell_full_v, defaults.battery.cell_full_v);
  EXPECT_EQ(shipped.battery.cell_empty_v, defaults.battery.cell_empty_v);
  EXPECT_EQ(shipped.battery.hover_current_a, defaults.battery.hover_current_a);
  EXPECT_EQ(shipped.battery.idle_current_a, defaults.battery.idle_current_a);
  EXPECT_EQ(shipped.battery.internal_resistance_ohm, defaults.battery.internal_resistance_ohm);
}

TEST(SimFcParams, BadValuesAndUnknownKeysAreNamed) {
  EXPECT_NE(error_of("sim_fc: {com_of_loss_t_s: 0}").find("sim_fc.com_of_loss_t_s"),
            std::string::npos);
  EXPECT_NE(error_of("sim_fc: {system_id_base: 0}").find("sim_fc.system_id_base"),
            std::string::npos);
  EXPECT_NE(error_of("sim_fc: {ugv_system_id_base: 2}").find("overlap"), std::string::npos);
  EXPECT_NE(error_of("sim_fc: {battery: {cell_full_v: 3.0}}").find("sim_fc.battery.cell_full_v"),
            std::string::npos);
  EXPECT_NE(error_of("sim_fc: {com_of_loss_s: 1}").find("com_of_loss_s"), std::string::npos);
  EXPECT_EQ(parse("sim_fc: {com_of_loss_t_s: 0.5}").com_of_loss_t_s, 0.5);
}

TEST(AutopilotMode, NamesAndDoSetModeParameters) {
  using cover::sim::fc::AutopilotProfile;
  using cover::sim::fc::FlightMode;
  using cover::sim::fc::parse_mode_name;
  using cover::sim::fc::requested_mode;
  EXPECT_EQ(parse_mode_name("posctl"), FlightMode::Position);
  EXPECT_EQ(parse_mode_name("LOITER"), FlightMode::Position);
  EXPECT_EQ(parse_mode_name("GUIDED_NOGPS"), FlightMode::Offboard);
  EXPECT_EQ(parse_mode_name("AUTO.LAND"), FlightMode::Land);
  EXPECT_FALSE(parse_mode_name("ACRO"));
  EXPECT_EQ(requested_mode(AutopilotProfile::Px4, 1, 6, 0), FlightMode::Offboard);
  EXPECT_EQ(requested_mode(AutopilotProfile::Px4, 1, 4, 6), FlightMode::Land);
  EXPECT_FALSE(requested_mode(AutopilotProfile::Px4, 1, 4, 3));  // AUTO.LOITER
  EXPECT_FALSE(requested_mode(AutopilotProfile::Px4, 0, 6, 0));  // no custom-mode flag
  EXPECT_EQ(requested_mode(AutopilotProfile::ArduPilot, 1, 20, 0), FlightMode::Offboard);
  EXPECT_FALSE(requested_mode(AutopilotProfile::ArduPilot, 1, 6.5F, 0));
}

}  // namespace

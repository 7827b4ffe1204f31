// config/sim/sim_fc.yaml: the shipped file writes every field (SimFcParams::fields) at its
// default; errors name the key and the bounds.
#include <gtest/gtest.h>

#include "cover/config/config_error.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/fc/autopilot_mode.hpp"
#include "cover/sim/fc/sim_fc_params.hpp"
#include "cover/test/shipped_params.hpp"

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

TEST(SimFcParams, ShippedFileHoldsEveryFieldAtItsDefault) {
  const std::string path = cover::config::default_config_dir() + "/sim/sim_fc.yaml";
  cover::test::expect_shipped_file_holds_defaults(SimFcParams::load_file(path), path, "sim_fc");
}

TEST(SimFcParams, BadValuesAndUnknownKeysAreNamed) {
  EXPECT_EQ(error_of("sim_fc: {px4: {com_of_loss_t_s: 0}}"),
            "sim_fc.px4.com_of_loss_t_s: must be in [0.01, 60] s");
  EXPECT_EQ(
      error_of("sim_fc: {system_id_base: 0}"),
      "sim_fc.system_id_base: must be in [1, 247] (UAVs 0..3 take system_id_base + u <= 250)");
  EXPECT_EQ(error_of("sim_fc: {ugv_system_id_base: 2}"),
            "sim_fc.ugv_system_id_base: must not overlap the UAVs' system ids");
  EXPECT_EQ(error_of("sim_fc: {px4: {streams: {attitude_hz: -1}}}"),
            "sim_fc.px4.streams.attitude_hz: must be in [0, 1000] Hz");
  EXPECT_EQ(error_of("sim_fc: {ardupilot: {streams: {heartbeat_hz: 0}}}"),
            "sim_fc.ardupilot.streams.heartbeat_hz: must be > 0 (an autopilot always sends "
            "HEARTBEAT)");
  EXPECT_EQ(error_of("sim_fc: {ardupilot: {atc_angle_boost: 2}}"),
            "sim_fc.ardupilot.atc_angle_boost: must be in [0, 1]");
  // Only PX4 streams message types the codec does not know.
  EXPECT_NE(error_of("sim_fc: {ardupilot: {streams: {codec_unknown_hz: 1}}}")
                .find("unknown key 'codec_unknown_hz'"),
            std::string::npos);
  EXPECT_EQ(error_of("sim_fc: {battery: {cell_full_v: 3.0}}"),
            "sim_fc.battery.cell_full_v: must exceed cell_empty_v");
  EXPECT_EQ(error_of("sim_fc: {battery: {cells: 11}}"), "sim_fc.battery.cells: must be in [1, 10]");
  EXPECT_NE(error_of("sim_fc: {com_of_loss_s: 1}").find("unknown key 'com_of_loss_s'"),
            std::string::npos);
  EXPECT_NE(error_of("sim_fc: {battery: {cell: 4}}").find("sim_fc.battery: unknown key 'cell'"),
            std::string::npos);
  EXPECT_EQ(parse("sim_fc: {px4: {com_of_loss_t_s: 0.5}}").px4.com_of_loss_t_s, 0.5);
}

// The firmware's parameters and stream rates are set in the file: a test sets a wrong one.
TEST(SimFcParams, FirmwareParametersAndStreamsComeFromTheFile) {
  const SimFcParams p = parse(
      "sim_fc: {ardupilot: {atc_angle_boost: 1, disarm_delay_s: 0, streams: {sys_status_hz: 2}},"
      " px4: {com_disarm_prflt_s: -1, streams: {highres_imu_hz: 100}}}");
  EXPECT_EQ(p.ardupilot.atc_angle_boost, 1);
  EXPECT_EQ(p.ardupilot.disarm_delay_s, 0);
  EXPECT_EQ(p.ardupilot.streams.sys_status_hz, 2.0);
  EXPECT_EQ(p.ardupilot.streams.highres_imu_hz, 0.0);  // ArduCopter's default: off
  EXPECT_EQ(p.px4.com_disarm_prflt_s, -1.0);
  EXPECT_EQ(p.px4.streams.highres_imu_hz, 100.0);
  EXPECT_EQ(p.px4.streams.attitude_hz, 100.0);  // PX4's onboard default
  EXPECT_EQ(p.px4.streams.battery_status_hz, 0.5);
}

TEST(AutopilotMode, NamesAndDoSetModeParameters) {
  using cover::Autopilot;
  using cover::sim::fc::FlightMode;
  using cover::sim::fc::parse_mode_name;
  using cover::sim::fc::requested_mode;
  EXPECT_EQ(parse_mode_name("posctl"), FlightMode::Position);
  EXPECT_EQ(parse_mode_name("LOITER"), FlightMode::Position);
  EXPECT_EQ(parse_mode_name("GUIDED_NOGPS"), FlightMode::Offboard);
  EXPECT_EQ(parse_mode_name("AUTO.LAND"), FlightMode::Land);
  EXPECT_EQ(parse_mode_name("auto.loiter"), FlightMode::Hold);
  EXPECT_FALSE(parse_mode_name("ACRO"));
  EXPECT_EQ(requested_mode(Autopilot::Px4, 1, 6, 0), FlightMode::Offboard);
  EXPECT_EQ(requested_mode(Autopilot::Px4, 1, 4, 6), FlightMode::Land);
  EXPECT_EQ(requested_mode(Autopilot::Px4, 1, 4, 3), FlightMode::Hold);  // AUTO.LOITER
  EXPECT_FALSE(requested_mode(Autopilot::Px4, 1, 4, 4));                 // AUTO.MISSION
  EXPECT_FALSE(requested_mode(Autopilot::Px4, 0, 6, 0));                 // no custom-mode flag
  EXPECT_EQ(requested_mode(Autopilot::ArduPilot, 1, 20, 0), FlightMode::Offboard);
  EXPECT_FALSE(requested_mode(Autopilot::ArduPilot, 1, 6.5F, 0));
}

}  // namespace

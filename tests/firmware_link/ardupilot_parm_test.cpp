// config/firmware/arducopter_json.parm against what it must say for COVER's commands to fly
// (docs/flight-controller.md) and against the plant it flies
// (config/sim/firmware_uav_arducopter.yaml): one motor curve and one hover on both sides.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>

#include "cover/firmware/params_file.hpp"
#include "cover/firmware/sitl_process.hpp"
#include "cover/sim/firmware_uav_params.hpp"
#include "cover/test/scratch_dir.hpp"

namespace cover::firmware {
namespace {

std::map<std::string, double> shipped() {
  std::map<std::string, double> values;
  for (const auto& [name, value] :
       read_params_file(COVER_CONFIG_DIR "/firmware/arducopter_json.parm")) {
    EXPECT_EQ(values.count(name), 0u) << name << " given twice";
    values[name] = std::stod(value);
  }
  return values;
}

TEST(ArduCopterJsonParm, SaysWhatCoverCommandsNeed) {
  auto p = shipped();
  EXPECT_EQ(p.at("FRAME_CLASS"), 1);
  EXPECT_EQ(p.at("FRAME_TYPE"), 1);  // quad X
  EXPECT_EQ(p.at("GUID_OPTIONS"), 8);
  EXPECT_EQ(p.at("ATC_ANGLE_BOOST"), 0);
  EXPECT_EQ(p.at("FS_THR_ENABLE"), 0);
  EXPECT_EQ(p.at("GPS1_TYPE"), 0);
  EXPECT_EQ(p.at("EK3_SRC1_POSXY"), 0);
  EXPECT_EQ(p.at("EK3_SRC1_VELXY"), 0);
  EXPECT_EQ(p.at("EK3_SRC1_VELZ"), 0);
}

TEST(ArduCopterJsonParm, MatchesThePlant) {
  auto p = shipped();
  const auto uav =
      sim::FirmwareUavParams::load_file(COVER_CONFIG_DIR "/sim/firmware_uav_arducopter.yaml");
  const auto& motor = uav.plant.motor;
  EXPECT_DOUBLE_EQ(p.at("MOT_SPIN_MIN"), motor.spin_min);
  EXPECT_DOUBLE_EQ(p.at("MOT_SPIN_MAX"), motor.spin_max);
  EXPECT_DOUBLE_EQ(p.at("MOT_THST_EXPO"), motor.thrust_expo);
  EXPECT_EQ(p.at("MOT_PWM_MIN"), 1000);  // the link's (pwm - 1000) / 1000
  EXPECT_EQ(p.at("MOT_PWM_MAX"), 2000);
  // ArduCopter's throttle is linear in thrust: hover = m g / (4 T_max).
  EXPECT_NEAR(p.at("MOT_THST_HOVER"), uav.plant.mass_kg * 9.81 / (4.0 * motor.max_thrust_n), 0.001);
  EXPECT_EQ(p.at("MOT_BAT_VOLT_MAX"), 0);  // no battery in the plant: no compensation
  // One SITL frame per physics step.
  EXPECT_EQ(p.at("SIM_RATE_HZ"), 1000);
  EXPECT_NO_THROW(sim::FirmwareUavParams::load_file(
      COVER_CONFIG_DIR "/sim/firmware_uav_arducopter.yaml", p.at("SIM_RATE_HZ")));
}

TEST(ReadParamsFile, ReadsArduPilotsFormsAndNamesTheBadLine) {
  const auto path = cover::test::scratch_dir() / "a.parm";
  {
    std::ofstream out(path);
    out << "# comment\n\nFRAME_TYPE\t1\nSIM_RATE_HZ,1000  # trailing\n  GUID_OPTIONS 8\n";
  }
  const auto params = read_params_file(path);
  ASSERT_EQ(params.size(), 3u);
  EXPECT_EQ(params[0], (std::pair<std::string, std::string>("FRAME_TYPE", "1")));
  EXPECT_EQ(params[1], (std::pair<std::string, std::string>("SIM_RATE_HZ", "1000")));
  EXPECT_EQ(params[2], (std::pair<std::string, std::string>("GUID_OPTIONS", "8")));
  {
    std::ofstream out(path);
    out << "FRAME_TYPE 1\nLONELY\n";
  }
  try {
    read_params_file(path);
    FAIL() << "a line without a value was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a.parm:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_params_file(cover::test::scratch_dir() / "none.parm"), std::runtime_error);
}

}  // namespace
}  // namespace cover::firmware

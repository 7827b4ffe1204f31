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

// The file's numbers; a value naming the instance's own system id (kOwnSystemId) is -1.
std::map<std::string, double> shipped() {
  std::map<std::string, double> values;
  for (const auto& [name, value] :
       read_params_file(COVER_CONFIG_DIR "/firmware/arducopter_json.parm")) {
    EXPECT_EQ(values.count(name), 0u) << name << " given twice";
    values[name] = value == kOwnSystemId ? -1.0 : std::stod(value);
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
  // The bridge's death lands the UAV: the GCS failsafe (Land) watches the bridge's
  // HEARTBEAT, which carries the vehicle's own system id.
  EXPECT_EQ(p.at("FS_GCS_ENABLE"), 5);
  EXPECT_GT(p.at("FS_GCS_TIMEOUT"), 0);
  EXPECT_LE(p.at("FS_GCS_TIMEOUT"), 5);
  EXPECT_EQ(p.at("MAV_GCS_SYSID"), -1) << "the instance's own system id, " << kOwnSystemId;
}

// The instance's own system id goes into the parameters ArduCopter loads as a number.
TEST(WriteArduCopterParams, WritesTheOwnSystemIdAsTheInstancesNumber) {
  const auto path = cover::test::scratch_dir() / "cover.parm";
  write_arducopter_params(path, {{"MAV_GCS_SYSID", kOwnSystemId}, {"FS_GCS_ENABLE", "5"}}, 8);
  const auto written = read_params_file(path);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0], (std::pair<std::string, std::string>("MAV_GCS_SYSID", "8")));
  EXPECT_EQ(written[1], (std::pair<std::string, std::string>("FS_GCS_ENABLE", "5")));
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

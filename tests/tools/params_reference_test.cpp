// docs/parameters.md against the parameter structs' declarations (cover-params): the page
// must be what the tool prints, and every struct with fields() must be on it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "params_reference.hpp"

namespace {

namespace fs = std::filesystem;
namespace ref = cover::params_reference;

const fs::path kSource = COVER_SOURCE_DIR;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Headers under the repository's module folders that declare a struct's fields(), relative
// to the repository root.
std::set<std::string> headers_with_fields() {
  std::set<std::string> found;
  for (const char* top : {"services", "uav_agent", "ugv_agent", "sim", "task_manager", "fc_bridge",
                          "mocap", "tools", "foxglove"}) {
    if (!fs::exists(kSource / top)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(kSource / top)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".hpp") continue;
      if (read_text(entry.path()).find("static void fields(Self& self") != std::string::npos) {
        found.insert(fs::relative(entry.path(), kSource).generic_string());
      }
    }
  }
  return found;
}

TEST(ParamsReference, DocsPageIsTheToolsOutput) {
  const fs::path page = kSource / "docs" / "parameters.md";
  ASSERT_TRUE(fs::exists(page)) << page << " is missing; generate it with\n"
                                << "  build/tools/cover-params/cover-params --markdown > "
                                   "docs/parameters.md";
  const std::string report = ref::drift_report(read_text(page), ref::markdown());
  EXPECT_TRUE(report.empty()) << report;
}

// A new parameter struct is either a section of the page or a sub-section of one (its keys
// dotted under a section's key): a struct nobody can find documented fails here.
TEST(ParamsReference, EveryStructWithFieldsIsDocumented) {
  // Headers whose structs appear only as sub-sections, with a key that shows them.
  const std::map<std::string, std::string> sub_sections = {
      {"services/config/include/cover/config/param_fields.hpp", ""},  // the machinery
      {"sim/include/cover/sim/quadrotor.hpp", "`uav.plant.mass_true_kg`"},
      {"sim/include/cover/sim/motor_quadrotor.hpp", "`plant.mass_kg`"},
      {"sim/include/cover/sim/motor_model.hpp", "`plant.motor.max_thrust_n`"},
      {"sim/include/cover/sim/rotor_geometry.hpp", "`plant.motor_1.position_flu_m`"},
      {"sim/include/cover/sim/uav_sensor_suite.hpp", "`sensors.imu.rate_hz`"},
      {"sim/include/cover/sim/uav_imu.hpp", "`sensors.imu.specific_force_noise_m_s2`"},
      {"sim/include/cover/sim/barometer.hpp", "`sensors.barometer.rate_hz`"},
      {"sim/include/cover/sim/magnetometer.hpp", "`sensors.magnetometer.rate_hz`"},
      {"sim/include/cover/sim/relative_sensor.hpp", "`relative_sensor.rate_hz`"},
      {"sim/include/cover/sim/imu_sensor.hpp", "`imu.rate_hz`"},
      {"sim/include/cover/sim/odometry_sensor.hpp", "`odometry.rate_hz`"},
      {"sim/include/cover/sim/ugv_motion_pattern.hpp", "`pattern.kind`"},
      {"ugv_agent/imu_filter/include/cover/ugv/imu_filter.hpp", "`imu_filter."},
      {"ugv_agent/speed_estimator/include/cover/ugv/speed_estimator.hpp", "`speed_estimator."},
      {"uav_agent/sampc/include/cover/sampc/intercept_velocity.hpp", "`intercept."},
  };
  std::set<std::string> sections;
  for (const ref::Section& s : ref::sections()) sections.insert(s.header);
  const std::string page = ref::markdown();
  for (const std::string& header : headers_with_fields()) {
    if (sections.count(header)) continue;
    const auto sub = sub_sections.find(header);
    if (sub == sub_sections.end()) {
      ADD_FAILURE() << header << " declares fields() but is no section of docs/parameters.md: "
                    << "add it to tools/cover-params/params_reference.cpp (or, if it is only "
                    << "a sub-section, to this test's list)";
    } else if (!sub->second.empty()) {
      EXPECT_NE(page.find(sub->second), std::string::npos)
          << header << ": " << sub->second << " not found on the page";
    }
  }
  for (const std::string& header : sections) {
    EXPECT_TRUE(fs::exists(kSource / header)) << "a section names " << header;
  }
}

TEST(ParamsReference, EverySectionHasATableOfKeys) {
  for (const ref::Section& s : ref::sections()) {
    EXPECT_EQ(s.table.rfind("| key | unit | default | valid | meaning |\n", 0), 0u) << s.title;
    EXPECT_NE(s.table.find("| `"), std::string::npos) << s.title << " lists no key";
    EXPECT_NE(s.intro.find("Read by"), std::string::npos) << s.title << ": no reader named";
  }
}

TEST(ParamsReference, DriftReportShowsTheChangeAndTheCommand) {
  EXPECT_EQ(ref::drift_report("a\nb\n", "a\nb\n"), "");
  const std::string report = ref::drift_report("a\nb\nc\nd\n", "a\nB\nc\nd\n");
  EXPECT_NE(report.find("@@ -2 +2 @@\n a\n-b\n+B\n c\n d\n"), std::string::npos) << report;
  EXPECT_NE(report.find("cover-params --markdown > docs/parameters.md"), std::string::npos);
  const std::string newline = ref::drift_report("a\nb", "a\nb\n");
  EXPECT_NE(newline.find("final newline"), std::string::npos) << newline;
}

}  // namespace

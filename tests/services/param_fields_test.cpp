// config/param_fields.hpp: a struct's one list of fields drives load, checks, keys, values
// and its documentation table.
#include "cover/config/param_fields.hpp"

#include <gtest/gtest.h>

#include <gtest/gtest-spi.h>

#include <Eigen/Core>
#include <fstream>
#include <string>

#include "cover/test/scratch_dir.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::config {
namespace {

struct Example {
  double period_s = 0.01;
  int count = 3;
  Eigen::Vector3d gains{1.0, 2.0, 3.0};
  std::string name = "x";

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    visit("period_s", self.period_s, Field("s", "control period").above(0.0).at_most(0.1));
    visit("count", self.count, Field("", "how many").at_least(1.0));
    visit("gains", self.gains, Field("1/s", "per axis").at_least(0.0));
    visit("name", self.name, Field("", "a label"));
  }
};

std::string error_of(const std::string& yaml) {
  try {
    YamlReader reader(YAML::Load(yaml), "example");
    Example e;
    load_fields(e, reader);
    check_fields(e, "example");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ParamFields, LoadsChecksAndNamesTheKey) {
  YamlReader reader(YAML::Load("{period_s: 0.02, gains: [0, 1, 2], name: y}"), "example");
  Example e;
  load_fields(e, reader);
  EXPECT_EQ(e.period_s, 0.02);
  EXPECT_EQ(e.count, 3) << "a key not written keeps its default";
  EXPECT_EQ(e.gains, Eigen::Vector3d(0, 1, 2));
  EXPECT_EQ(e.name, "y");

  EXPECT_EQ(error_of("period_s: 0.2"), "example.period_s: must be in (0, 0.1] s");
  EXPECT_EQ(error_of("period_s: 0"), "example.period_s: must be in (0, 0.1] s");
  EXPECT_EQ(error_of("period_s: .inf"), "example.period_s: must be in (0, 0.1] s");
  EXPECT_EQ(error_of("count: 0"), "example.count: must be >= 1");
  EXPECT_EQ(error_of("gains: [1, -1, 1]"), "example.gains: each must be >= 0 1/s");
  EXPECT_NE(error_of("perod_s: 0.01").find("perod_s"), std::string::npos)
      << "a key that is no field is rejected";
  EXPECT_EQ(error_of("{period_s: 0.1, count: 1}"), "accepted");
}

TEST(ParamFields, KeysValuesAndTableFollowTheOneList) {
  EXPECT_EQ(field_keys<Example>(),
            (std::vector<std::string>{"period_s", "count", "gains", "name"}));
  Example changed;
  changed.gains.z() = 4.0;
  const auto defaults = field_values(Example{});
  const auto values = field_values(changed);
  EXPECT_EQ(defaults[2].second, "1, 2, 3");
  EXPECT_NE(values, defaults);
  const std::string table = field_table<Example>();
  EXPECT_NE(table.find("| `period_s` | s | 0.01 | (0, 0.1] | control period |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| `count` |  | 3 | >= 1 | how many |"), std::string::npos) << table;
}

// Every other kind of field: bool, enum, string of fixed words, required, below(), a
// sub-section (twice: once without some of its keys).
enum class Gear { Low, High };
const char* to_string(Gear gear) {
  return gear == Gear::Low ? "low" : "high";
}

struct Limits {
  double lag_rad = 0.5;
  double gain = 0.0;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    visit("lag_rad", self.lag_rad, Field("rad", "lag").above(0.0).below(1.5));
    visit("gain", self.gain, Field("1/s", "gain").at_least(0.0).hint("0 disables"));
  }
};

struct Vehicle {
  bool armed = false;
  Gear gear = Gear::High;
  std::string autopilot = "px4";
  int id = 1;
  Limits limits;
  Limits fallback;

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    visit("armed", self.armed, Field("", "armed at start"));
    visit("gear", self.gear, Field("", "which gear").one_of({Gear::Low, Gear::High}));
    visit("autopilot", self.autopilot, Field("", "its firmware").one_of({"px4", "ardupilot"}));
    visit("id", self.id, Field("", "its number").at_least(1.0).required());
    visit("limits", self.limits, Field("", "the limits"));
    visit("fallback", self.fallback, Field("", "the fallback's limits").without({"gain"}));
  }
};

std::string vehicle_error(const std::string& yaml) {
  try {
    YamlReader reader(YAML::Load(yaml), "vehicle");
    Vehicle v;
    load_fields(v, reader);
    check_fields(v, "vehicle");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ParamFields, LoadsBoolsWordsEnumsAndSubSections) {
  YamlReader reader(YAML::Load("{armed: true, gear: low, autopilot: ardupilot, id: 4,"
                               " limits: {lag_rad: 1.2}, fallback: {lag_rad: 0.1}}"),
                    "vehicle");
  Vehicle v;
  load_fields(v, reader);
  EXPECT_TRUE(v.armed);
  EXPECT_EQ(v.gear, Gear::Low);
  EXPECT_EQ(v.autopilot, "ardupilot");
  EXPECT_EQ(v.id, 4);
  EXPECT_EQ(v.limits.lag_rad, 1.2);
  EXPECT_EQ(v.limits.gain, 0.0) << "a sub-section's key not written keeps its default";
  EXPECT_EQ(v.fallback.lag_rad, 0.1);
  EXPECT_EQ(vehicle_error("{id: 1, limits: {}}"), "accepted") << "an empty sub-section";
}

TEST(ParamFields, RejectsWithTheDottedKey) {
  EXPECT_EQ(vehicle_error("{id: 1, gear: reverse}"),
            "vehicle.gear: 'reverse' is not one of low, high (line 1)");
  EXPECT_EQ(vehicle_error("{id: 1, autopilot: betaflight}"),
            "vehicle.autopilot: 'betaflight' is not one of px4, ardupilot (line 1)");
  EXPECT_EQ(vehicle_error("{armed: false}"), "vehicle.id: missing required key (line 1)");
  EXPECT_EQ(vehicle_error("{id: 1, limits: {lag_rads: 1}}"),
            "vehicle.limits: unknown key 'lag_rads' (line 1)");
  EXPECT_EQ(vehicle_error("{id: 1, fallback: {gain: 1}}"),
            "vehicle.fallback: unknown key 'gain' (line 1)")
      << "a key the sub-section is declared without";
  EXPECT_EQ(vehicle_error("{id: 1, limits: {lag_rad: 1.5}}"),
            "vehicle.limits.lag_rad: must be in (0, 1.5) rad");
  EXPECT_EQ(vehicle_error("{id: 1, limits: {gain: -1}}"),
            "vehicle.limits.gain: must be >= 0 1/s (0 disables)");
  EXPECT_EQ(vehicle_error("{id: 1, limits: 3}"), "vehicle.limits: expected a mapping");
  EXPECT_NE(vehicle_error("{id: 1, armed: maybe}").find("vehicle.armed: wrong type"),
            std::string::npos);

  Vehicle in_code;
  in_code.autopilot = "apm";
  try {
    check_fields(in_code, "vehicle");
    ADD_FAILURE() << "a word set in code is checked too";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "vehicle.autopilot: 'apm' is not one of px4, ardupilot");
  }
}

TEST(ParamFields, SubSectionKeysAreDottedInKeysValuesAndTable) {
  EXPECT_EQ(field_keys<Vehicle>(),
            (std::vector<std::string>{"armed", "gear", "autopilot", "id", "limits.lag_rad",
                                      "limits.gain", "fallback.lag_rad"}));
  const auto values = field_values(Vehicle{});
  EXPECT_EQ(values[0].second, "false");
  EXPECT_EQ(values[1].second, "high");
  EXPECT_EQ(values[2].second, "px4");
  Example precise;
  precise.period_s = 0.1 + 1e-12;
  EXPECT_NE(field_values(precise), field_values(Example{}))
      << "values compare exactly, not to 6 digits";

  const std::string table = field_table<Vehicle>();
  EXPECT_NE(table.find("| `gear` |  | high | one of low, high | which gear |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| `armed` |  | false | true, false | armed at start |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| `id` |  | 1 | >= 1 (required) | its number |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| `limits.lag_rad` | rad | 0.5 | (0, 1.5) | lag |"), std::string::npos)
      << table;
  EXPECT_EQ(table.find("fallback.gain"), std::string::npos) << table;
}

// The shipped-file helpers: every dotted key written, and (where the file states the
// defaults) every value the default.
TEST(ParamFields, ShippedFileHelpersFindAMissingKeyAndAChangedValue) {
  const std::string path = cover::test::scratch_path("vehicle.yaml");
  std::ofstream(path) << "top:\n  vehicle:\n    armed: false\n    gear: high\n"
                         "    autopilot: px4\n    id: 1\n    limits: {lag_rad: 0.5, gain: 0}\n"
                         "    fallback: {lag_rad: 0.5}\n";
  cover::test::expect_shipped_file_holds_defaults(Vehicle{}, path, "top.vehicle");

  const std::string partial = cover::test::scratch_path("partial.yaml");
  std::ofstream(partial) << "vehicle:\n  armed: false\n  gear: high\n  autopilot: px4\n  id: 1\n"
                            "  limits: {lag_rad: 0.5}\n  fallback: {lag_rad: 0.5}\n";
  EXPECT_NONFATAL_FAILURE(
      cover::test::expect_shipped_file_holds_every_field<Vehicle>(partial, "vehicle"),
      "vehicle.limits.gain is a field but the shipped file does not write it");
  Vehicle changed;
  changed.limits.gain = 2.0;
  EXPECT_NONFATAL_FAILURE(
      cover::test::expect_shipped_file_holds_defaults(changed, path, "top.vehicle"),
      "top.vehicle.limits.gain differs from its default");
}

}  // namespace
}  // namespace cover::config

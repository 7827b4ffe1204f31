// config/param_fields.hpp: a struct's one list of fields drives load, checks, keys, values
// and its documentation table.
#include "cover/config/param_fields.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

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

  EXPECT_EQ(error_of("period_s: 0.2"), "example.period_s: must be in (0, 0.1]");
  EXPECT_EQ(error_of("period_s: 0"), "example.period_s: must be in (0, 0.1]");
  EXPECT_EQ(error_of("period_s: .inf"), "example.period_s: must be in (0, 0.1]");
  EXPECT_EQ(error_of("count: 0"), "example.count: must be >= 1");
  EXPECT_EQ(error_of("gains: [1, -1, 1]"), "example.gains: each must be >= 0");
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

}  // namespace
}  // namespace cover::config

// config/uav_agent.yaml: every key shipped at its default, bounds and the checks between keys
// named by their dotted key (UavAgentParams::fields).
#include "uav_agent_params.hpp"

#include <gtest/gtest.h>

#include <string>

#include "cover/config/config_error.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::uav_agent {
namespace {

TEST(UavAgentParams, ShippedFileHoldsEveryFieldAtItsDefault) {
  const std::string path = config::default_config_dir() + "/uav_agent.yaml";
  const UavAgentParams shipped = UavAgentParams::load_file(path);
  cover::test::expect_shipped_file_holds_defaults(shipped, path, "uav_agent");
}

std::string error_of(const std::string& yaml) {
  try {
    UavAgentParams::from_yaml(config::parse_yaml(yaml, "a.yaml"), "a.yaml");
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(UavAgentParams, ErrorsNameTheDottedKey) {
  EXPECT_EQ(error_of("uav_agent: {control_cpu: 1, spin_after_rehearsal_s: 0.0005}"), "accepted");
  EXPECT_EQ(error_of("uav_agent: {control_cpu: -2}"),
            "a.yaml.uav_agent.control_cpu: must be in [-1, 1023]");
  EXPECT_EQ(error_of("uav_agent: {rehearsal_lead_s: 0.005}"),
            "a.yaml.uav_agent.rehearsal_lead_s: must be in [0, 0.005) s");
  EXPECT_EQ(error_of("uav_agent: {status_period: 1}"),
            "a.yaml.uav_agent: unknown key 'status_period' (line 1)");
}

}  // namespace
}  // namespace cover::uav_agent

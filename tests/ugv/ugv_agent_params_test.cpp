// config/ugv_agent.yaml: the agent's keys and its filter's and speed estimator's sub-sections,
// one declaration each (UgvAgentParams::fields and theirs).
#include "ugv_agent_params.hpp"

#include <gtest/gtest.h>

#include <string>

#include "cover/test/shipped_params.hpp"

namespace cover::ugv {
namespace {

// Every field, the sub-sections' by dotted keys, shipped with its default value; the filter
// and the estimator read alone from the same file (the simulator, the harness) agree.
TEST(UgvAgentParams, ShippedFileHoldsEveryFieldAtItsDefault) {
  const std::string path = config::default_config_dir() + "/ugv_agent.yaml";
  const UgvAgentParams shipped = UgvAgentParams::load_file(path);
  cover::test::expect_shipped_file_holds_defaults(shipped, path, "ugv_agent");
  EXPECT_EQ(config::field_values(ImuFilterParams::load_default()),
            config::field_values(shipped.imu_filter));
  EXPECT_EQ(config::field_values(SpeedEstimatorParams::load_default()),
            config::field_values(shipped.speed_estimator));
}

TEST(UgvAgentParams, ErrorsNameTheDottedKey) {
  const auto error_of = [](const std::string& yaml) {
    try {
      UgvAgentParams::from_yaml(config::parse_yaml(yaml, "u.yaml"), "u.yaml");
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error_of("ugv_agent: {status_rate_hz: 2}"), "accepted");
  EXPECT_EQ(error_of("ugv_agent: {imu_filter: {max_sample_gap_s: 0}}"),
            "u.yaml.ugv_agent.imu_filter.max_sample_gap_s: must be > 0 s");
  EXPECT_EQ(error_of("ugv_agent: {speed_estimator: {max_speed_m_s: 200}}"),
            "u.yaml.ugv_agent.speed_estimator.max_speed_m_s: must be in (0, 100] m/s");
  EXPECT_EQ(error_of("ugv_agent: {speed_estimator: {max_speed: 2}}"),
            "u.yaml.ugv_agent.speed_estimator: unknown key 'max_speed' (line 1)");
  EXPECT_EQ(error_of("ugv_agent: {segment_wait_s: -1}"),
            "u.yaml.ugv_agent.segment_wait_s: must be in [0, 3600] s");
}

}  // namespace
}  // namespace cover::ugv

// config/sim/sim_process.yaml: every field (SimProcessParams::fields) at its default.
#include <gtest/gtest.h>

#include <string>

#include "cover/config/config_error.hpp"
#include "cover/test/shipped_params.hpp"
#include "sim_process_params.hpp"

namespace cover::sim {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    SimProcessParams::from_yaml(config::parse_yaml(yaml, "test.yaml"), "test.yaml");
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SimProcessParams, ShippedFileHoldsEveryFieldAtItsDefault) {
  const std::string path = config::default_config_dir() + "/sim/sim_process.yaml";
  test::expect_shipped_file_holds_defaults(SimProcessParams::load_file(path), path, "sim_process");
}

TEST(SimProcessParams, ErrorsNameTheKeyAndTheBounds) {
  EXPECT_EQ(error_of("sim_process: {offboard_timeout_s: 0}"),
            "sim_process.offboard_timeout_s: must be > 0 s");
  EXPECT_EQ(error_of("sim_process: {loss_descent_rate_m_s: 4}"),
            "sim_process.loss_descent_rate_m_s: must be in (0, 3] m/s");
  EXPECT_EQ(error_of("sim_process: {control_rate_hz: .inf}"),
            "sim_process.control_rate_hz: must be in (0, 1000] Hz");
  EXPECT_NE(error_of("sim_process: {stall_timeout: 1}").find("unknown key 'stall_timeout'"),
            std::string::npos);
  EXPECT_NE(error_of("other: {}").find("missing section 'sim_process'"), std::string::npos);
  EXPECT_EQ(error_of("sim_process: {stall_timeout_s: 1}"), "accepted");
}

}  // namespace
}  // namespace cover::sim

#include "cover/planner/planner_params.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "cover/test/scratch_dir.hpp"
#include "cover/test/shipped_params.hpp"

namespace cover::planner {
namespace {

std::string write_temp_yaml(const std::string& name, const std::string& text) {
  const std::string path = cover::test::scratch_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string load_error(const std::string& yaml) {
  try {
    PlannerParams::load_file(write_temp_yaml("planner_params_test.yaml", yaml));
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return {};
}

// The shipped file documents the defaults: every field (PlannerParams::fields), shipped
// with its default value.
TEST(PlannerParams, ShippedFileMatchesDefaults) {
  const std::string path = config::default_config_dir() + "/planner.yaml";
  cover::test::expect_shipped_file_holds_defaults(PlannerParams::load_file(path), path, "planner");
  EXPECT_NO_THROW(PlannerParams{}.validate());
}

TEST(PlannerParams, ReadsValues) {
  const auto path =
      write_temp_yaml("planner_ok.yaml", "planner:\n  pieces: 7\n  time_weight: 10.0\n");
  const PlannerParams params = PlannerParams::load_file(path);
  EXPECT_EQ(params.pieces, 7);
  EXPECT_EQ(params.time_weight, 10.0);
}

TEST(PlannerParams, ErrorsNameTheKey) {
  EXPECT_NE(load_error("planner:\n  peices: 3\n").find("peices"), std::string::npos);
  EXPECT_NE(load_error("planner:\n  pieces: 0\n").find("pieces"), std::string::npos);
  EXPECT_NE(load_error("planner:\n  time_weight: -1\n").find("time_weight"), std::string::npos);
  EXPECT_NE(load_error("planner:\n  samples_per_piece: abc\n").find("samples_per_piece"),
            std::string::npos);
  EXPECT_NE(load_error("planner:\n  overspeed_decel_fraction: 1.5\n").find("overspeed"),
            std::string::npos);
  EXPECT_NE(load_error("planer:\n  pieces: 3\n").find("planer"), std::string::npos);
}

}  // namespace
}  // namespace cover::planner

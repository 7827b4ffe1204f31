#include "cover/planner/planner_params.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include "cover/test/scratch_dir.hpp"

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

// The shipped file documents the defaults: loading it must give the struct's defaults.
TEST(PlannerParams, ShippedFileMatchesDefaults) {
  const PlannerParams shipped =
      PlannerParams::load_file(config::default_config_dir() + "/planner.yaml");
  const PlannerParams defaults;
  EXPECT_EQ(shipped.pieces, defaults.pieces);
  EXPECT_EQ(shipped.time_weight, defaults.time_weight);
  EXPECT_EQ(shipped.speed_penalty_weight, defaults.speed_penalty_weight);
  EXPECT_EQ(shipped.acc_penalty_weight, defaults.acc_penalty_weight);
  EXPECT_EQ(shipped.samples_per_piece, defaults.samples_per_piece);
  EXPECT_EQ(shipped.overspeed_decel_fraction, defaults.overspeed_decel_fraction);
  EXPECT_EQ(shipped.relative_cost_tolerance, defaults.relative_cost_tolerance);
  EXPECT_EQ(shipped.relative_step_tolerance, defaults.relative_step_tolerance);
  EXPECT_EQ(shipped.max_evaluations, defaults.max_evaluations);
  EXPECT_EQ(shipped.max_solve_time_s, defaults.max_solve_time_s);
  EXPECT_EQ(shipped.lbfgs_memory, defaults.lbfgs_memory);
  EXPECT_EQ(shipped.min_piece_duration_s, defaults.min_piece_duration_s);
  EXPECT_EQ(shipped.max_abs_speed_m_s, defaults.max_abs_speed_m_s);
  EXPECT_EQ(shipped.default_vmax_m_s, defaults.default_vmax_m_s);
  EXPECT_EQ(shipped.default_amax_m_s2, defaults.default_amax_m_s2);
  EXPECT_NO_THROW(defaults.validate());
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

#include "cover/planner/planner_params.hpp"

#include <cmath>

namespace cover::planner {

PlannerParams PlannerParams::load(config::YamlReader& reader) {
  PlannerParams params;
  reader.optional("pieces", params.pieces);
  reader.optional("time_weight", params.time_weight);
  reader.optional("speed_penalty_weight", params.speed_penalty_weight);
  reader.optional("acc_penalty_weight", params.acc_penalty_weight);
  reader.optional("samples_per_piece", params.samples_per_piece);
  reader.optional("overspeed_decel_fraction", params.overspeed_decel_fraction);
  reader.optional("relative_cost_tolerance", params.relative_cost_tolerance);
  reader.optional("relative_step_tolerance", params.relative_step_tolerance);
  reader.optional("max_evaluations", params.max_evaluations);
  reader.optional("max_solve_time_s", params.max_solve_time_s);
  reader.optional("lbfgs_memory", params.lbfgs_memory);
  reader.optional("min_piece_duration_s", params.min_piece_duration_s);
  reader.optional("default_vmax_m_s", params.default_vmax_m_s);
  reader.optional("default_amax_m_s2", params.default_amax_m_s2);
  reader.optional("at_goal_tolerance_m", params.at_goal_tolerance_m);
  reader.optional("at_rest_tolerance_m_s", params.at_rest_tolerance_m_s);
  reader.optional("max_abs_position_m", params.max_abs_position_m);
  reader.optional("max_abs_speed_m_s", params.max_abs_speed_m_s);
  reader.optional("max_abs_angular_rate_rad_s", params.max_abs_angular_rate_rad_s);
  reader.optional("max_limit_m_s", params.max_limit_m_s);
  reader.optional("max_limit_m_s2", params.max_limit_m_s2);
  reader.reject_unknown_keys();
  params.validate();
  return params;
}

PlannerParams PlannerParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

PlannerParams PlannerParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "planner", /*required=*/false);
  return load(reader);
}

void PlannerParams::validate() const {
  using config::check;
  const std::string ctx = "planner";
  auto positive = [&](double value, const char* key) {
    check(std::isfinite(value) && value > 0.0, ctx + "." + key, "must be a finite number > 0");
  };
  check(pieces >= 1 && pieces <= 20, ctx + ".pieces", "must be in [1, 20]");
  check(samples_per_piece >= 2 && samples_per_piece <= 200, ctx + ".samples_per_piece",
        "must be in [2, 200]");
  positive(time_weight, "time_weight");
  positive(speed_penalty_weight, "speed_penalty_weight");
  positive(acc_penalty_weight, "acc_penalty_weight");
  check(std::isfinite(overspeed_decel_fraction) && overspeed_decel_fraction > 0.0 &&
            overspeed_decel_fraction <= 1.0,
        ctx + ".overspeed_decel_fraction", "must be in (0, 1]");
  check(std::isfinite(relative_cost_tolerance) && relative_cost_tolerance >= 0.0,
        ctx + ".relative_cost_tolerance", "must be >= 0");
  check(std::isfinite(relative_step_tolerance) && relative_step_tolerance >= 0.0,
        ctx + ".relative_step_tolerance", "must be >= 0");
  check(relative_cost_tolerance > 0.0 || relative_step_tolerance > 0.0 || max_evaluations > 0, ctx,
        "needs at least one stopping rule");
  check(max_evaluations >= 1, ctx + ".max_evaluations", "must be >= 1");
  check(std::isfinite(max_solve_time_s) && max_solve_time_s >= 0.0, ctx + ".max_solve_time_s",
        "must be >= 0 (0: no wall-clock budget)");
  check(lbfgs_memory >= 1 && lbfgs_memory <= 50, ctx + ".lbfgs_memory", "must be in [1, 50]");
  check(std::isfinite(min_piece_duration_s) && min_piece_duration_s >= 0.0 &&
            min_piece_duration_s <= 1.0,
        ctx + ".min_piece_duration_s", "must be in [0, 1] s");
  positive(default_vmax_m_s, "default_vmax_m_s");
  positive(default_amax_m_s2, "default_amax_m_s2");
  positive(at_goal_tolerance_m, "at_goal_tolerance_m");
  positive(at_rest_tolerance_m_s, "at_rest_tolerance_m_s");
  positive(max_abs_position_m, "max_abs_position_m");
  positive(max_abs_speed_m_s, "max_abs_speed_m_s");
  positive(max_abs_angular_rate_rad_s, "max_abs_angular_rate_rad_s");
  positive(max_limit_m_s, "max_limit_m_s");
  positive(max_limit_m_s2, "max_limit_m_s2");
  check(default_vmax_m_s <= max_limit_m_s, ctx + ".default_vmax_m_s", "exceeds max_limit_m_s");
  check(default_amax_m_s2 <= max_limit_m_s2, ctx + ".default_amax_m_s2", "exceeds max_limit_m_s2");
}

}  // namespace cover::planner

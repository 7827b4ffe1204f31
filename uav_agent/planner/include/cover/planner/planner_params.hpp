#pragma once

#include <string>

#include "cover/config/yaml_reader.hpp"

namespace cover::planner {

// Tuning of the stage planner (config/planner.yaml, section `planner`). Every key is
// optional; the defaults below are the shipped values and are documented there too.
struct PlannerParams {
  // MINCO pieces M per stage; the optimiser has 3(M-1) waypoint and M duration variables.
  int pieces = 5;
  // rho: cost per second of duration, traded against integral ||jerk||^2 (m^2/s^5).
  double time_weight = 256.0;
  // Weights of the cubic time-integral penalties on the normalised excess
  // (|v|^2 - vm^2) / vm^2 and (|a|^2 - am^2) / am^2 (eqs. 16-18, normalised so one weight
  // fits every limit).
  double speed_penalty_weight = 2.0e5;
  double acc_penalty_weight = 1.0e6;
  // kappa: trapezoid samples per piece for the penalties (kappa + 1 points).
  int samples_per_piece = 8;
  // Initial speed above vm (unavoidable at t = 0): the speed limit starts at |v0| and
  // comes down to vm at this fraction of am, so the reference must slow down, not jump.
  double overspeed_decel_fraction = 0.5;
  // L-BFGS stopping rules (lbfgs.hpp): relative cost decrease, relative step per variable,
  // evaluation and wall-clock budgets, curvature pairs kept.
  double relative_cost_tolerance = 1.0e-5;
  double relative_step_tolerance = 1.0e-5;
  int max_evaluations = 400;
  // 0: none. A plan's work is bounded by max_evaluations: a wall-clock budget would make a
  // plan, and so a lockstep run, depend on the machine's load.
  double max_solve_time_s = 0.0;
  int lbfgs_memory = 8;
  // Floor added to every piece duration by the time map: keeps MINCO's matrix (powers of T
  // up to T^5) well conditioned when the optimum would collapse a piece (tiny stages).
  double min_piece_duration_s = 0.02;
  // Limits used when the caller gives none (cover-plan without --vmax/--amax).
  double default_vmax_m_s = 1.0;
  double default_amax_m_s2 = 2.0;
  // Start this close to the goal and this slow: the plan is "hold the start".
  double at_goal_tolerance_m = 1.0e-6;
  double at_rest_tolerance_m_s = 1.0e-6;
  // Input sanity bounds: anything beyond is InvalidInput (a corrupted estimate, not a stage).
  double max_abs_position_m = 1000.0;
  double max_abs_speed_m_s = 10.0;
  double max_abs_angular_rate_rad_s = 10.0;
  double max_limit_m_s = 30.0;    // vmax above this is absurd
  double max_limit_m_s2 = 100.0;  // amax above this is absurd

  static PlannerParams load(config::YamlReader& reader);
  // Reads the `planner` section of a YAML file; throws config::ConfigError naming the key.
  static PlannerParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static PlannerParams from_yaml(const YAML::Node& document, const std::string& source);
  // Throws config::ConfigError naming the offending key.
  void validate() const;
};

}  // namespace cover::planner

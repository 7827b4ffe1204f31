#pragma once

#include <string>

#include "cover/config/param_fields.hpp"

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

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list. Bounds against other fields are in validate().
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("pieces", self.pieces, Field("", "MINCO pieces M per stage").at_least(1.0).at_most(20.0));
    visit("time_weight", self.time_weight,
          Field("m^2/s^6", "rho: cost per second of duration").above(0.0));
    visit("speed_penalty_weight", self.speed_penalty_weight,
          Field("", "weight of the normalised speed excess penalty").above(0.0));
    visit("acc_penalty_weight", self.acc_penalty_weight,
          Field("", "weight of the normalised acceleration excess penalty").above(0.0));
    visit("samples_per_piece", self.samples_per_piece,
          Field("", "kappa: penalty samples per piece").at_least(2.0).at_most(200.0));
    visit("overspeed_decel_fraction", self.overspeed_decel_fraction,
          Field("", "an initial overspeed comes down at this fraction of amax")
              .above(0.0)
              .at_most(1.0));
    visit("relative_cost_tolerance", self.relative_cost_tolerance,
          Field("", "L-BFGS stops below this relative cost decrease").at_least(0.0));
    visit("relative_step_tolerance", self.relative_step_tolerance,
          Field("", "L-BFGS stops below this relative step per variable").at_least(0.0));
    visit("max_evaluations", self.max_evaluations,
          Field("", "L-BFGS evaluation budget").at_least(1.0));
    visit("max_solve_time_s", self.max_solve_time_s,
          Field("s", "wall-clock budget of a plan").at_least(0.0).hint("0: no wall-clock budget"));
    visit("lbfgs_memory", self.lbfgs_memory,
          Field("", "L-BFGS curvature pairs kept").at_least(1.0).at_most(50.0));
    visit("min_piece_duration_s", self.min_piece_duration_s,
          Field("s", "floor added to every piece duration").at_least(0.0).at_most(1.0));
    visit("default_vmax_m_s", self.default_vmax_m_s,
          Field("m/s", "speed limit when the caller gives none; <= max_limit_m_s").above(0.0));
    visit("default_amax_m_s2", self.default_amax_m_s2,
          Field("m/s^2", "acceleration limit when the caller gives none; <= max_limit_m_s2")
              .above(0.0));
    visit("at_goal_tolerance_m", self.at_goal_tolerance_m,
          Field("m", "this close to the goal (and at rest) the plan holds the start").above(0.0));
    visit("at_rest_tolerance_m_s", self.at_rest_tolerance_m_s,
          Field("m/s", "this slow (and at the goal) the plan holds the start").above(0.0));
    visit("max_abs_position_m", self.max_abs_position_m,
          Field("m", "input sanity: |position| beyond is InvalidInput").above(0.0));
    visit("max_abs_speed_m_s", self.max_abs_speed_m_s,
          Field("m/s", "input sanity: |velocity| beyond is InvalidInput").above(0.0));
    visit("max_abs_angular_rate_rad_s", self.max_abs_angular_rate_rad_s,
          Field("rad/s", "input sanity: |rate| beyond is InvalidInput").above(0.0));
    visit("max_limit_m_s", self.max_limit_m_s,
          Field("m/s", "a vmax above this is absurd").above(0.0));
    visit("max_limit_m_s2", self.max_limit_m_s2,
          Field("m/s^2", "an amax above this is absurd").above(0.0));
  }

  static PlannerParams load(config::YamlReader& reader);
  // Reads the `planner` section of a YAML file; throws config::ConfigError naming the key.
  static PlannerParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static PlannerParams from_yaml(const YAML::Node& document, const std::string& source);
  // Throws config::ConfigError naming the offending key.
  void validate() const;
};

}  // namespace cover::planner

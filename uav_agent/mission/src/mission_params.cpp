#include "cover/mission/mission_params.hpp"

#include <cmath>

#include "cover/config/format_number.hpp"

namespace cover::mission {
namespace {
bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}

AbortAction parse_abort_action(const std::string& text, const std::string& context) {
  for (const AbortAction action : {AbortAction::Hover, AbortAction::Land}) {
    if (text == to_string(action)) return action;
  }
  throw config::ConfigError(context + ".abort_action: '" + text + "' is not hover | land");
}

TransitionReference parse_transition_reference(const std::string& text,
                                               const std::string& context) {
  for (const TransitionReference reference :
       {TransitionReference::Planned, TransitionReference::RadialApproach}) {
    if (text == to_string(reference)) return reference;
  }
  throw config::ConfigError(context + ".transition_reference: '" + text +
                            "' is not planned | radial-approach");
}
}  // namespace

const char* to_string(AbortAction action) {
  switch (action) {
    case AbortAction::Hover:
      return "hover";
    case AbortAction::Land:
      return "land";
  }
  return "unknown";
}

const char* to_string(TransitionReference reference) {
  switch (reference) {
    case TransitionReference::Planned:
      return "planned";
    case TransitionReference::RadialApproach:
      return "radial-approach";
  }
  return "unknown";
}

MissionParams MissionParams::load(config::YamlReader& reader) {
  MissionParams params;
  reader.optional("reach_tolerance_m", params.reach_tolerance_m);
  reader.optional("speed_threshold_m_s", params.speed_threshold_m_s);
  reader.optional("transition_reach_tolerance_m", params.transition_reach_tolerance_m);
  reader.optional("action_tolerance_m", params.action_tolerance_m);
  reader.optional("action_speed_threshold_m_s", params.action_speed_threshold_m_s);
  reader.optional("initial_timeout_s", params.initial_timeout_s);
  reader.optional("transition_timeout_s", params.transition_timeout_s);
  reader.optional("final_timeout_s", params.final_timeout_s);
  reader.optional("state_timeout_s", params.state_timeout_s);
  reader.optional("imu_timeout_s", params.imu_timeout_s);
  reader.optional("imu_hold_s", params.imu_hold_s);
  reader.optional("emergency_hover_s", params.emergency_hover_s);
  reader.optional("emergency_descent_rate_m_s", params.emergency_descent_rate_m_s);
  reader.optional("emergency_level_gain_1_s", params.emergency_level_gain_1_s);
  reader.optional("emergency_height_gain_1_s2", params.emergency_height_gain_1_s2);
  reader.optional("emergency_speed_gain_1_s", params.emergency_speed_gain_1_s);
  reader.optional("emergency_integral_gain_1_s3", params.emergency_integral_gain_1_s3);
  reader.optional("emergency_integral_limit_m_s2", params.emergency_integral_limit_m_s2);
  reader.optional("emergency_blind_floor_m", params.emergency_blind_floor_m);
  reader.optional("max_plan_attempts", params.max_plan_attempts);
  reader.optional("plan_adopt_steps", params.plan_adopt_steps);
  reader.optional("integral_gain_1_s3", params.integral_gain_1_s3);
  reader.optional("integral_error_clip_m", params.integral_error_clip_m);
  reader.optional("integral_limit_m_s2", params.integral_limit_m_s2);
  reader.optional("observer_window_s", params.observer_window_s);
  reader.optional("observer_time_constant_s", params.observer_time_constant_s);
  reader.optional("abort_hold_s", params.abort_hold_s);
  std::string abort_action = to_string(params.abort_action);
  reader.optional("abort_action", abort_action);
  params.abort_action = parse_abort_action(abort_action, reader.context());
  reader.optional("abort_descent_rate_m_s", params.abort_descent_rate_m_s);
  reader.optional("land_detect_gap_m", params.land_detect_gap_m);
  reader.optional("land_detect_speed_m_s", params.land_detect_speed_m_s);
  reader.optional("land_detect_time_s", params.land_detect_time_s);
  std::string transition_reference = to_string(params.transition_reference);
  reader.optional("transition_reference", transition_reference);
  params.transition_reference = parse_transition_reference(transition_reference, reader.context());
  reader.optional("approach_brake_fraction", params.approach_brake_fraction);
  reader.optional("approach_speed_up_ramp_s", params.approach_speed_up_ramp_s);
  reader.optional("final_start_acceleration_fraction", params.final_start_acceleration_fraction);
  reader.optional("control_period_s", params.control_period_s);
  reader.reject_unknown_keys();
  params.validate();
  return params;
}

MissionParams MissionParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

MissionParams MissionParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader section =
      config::open_section(document, source, "mission", /*required=*/false);
  return load(section);
}

void MissionParams::validate() const {
  const std::string ctx = "mission";
  config::check(positive(reach_tolerance_m), ctx + ".reach_tolerance_m", "must be > 0");
  config::check(positive(transition_reach_tolerance_m), ctx + ".transition_reach_tolerance_m",
                "must be > 0");
  config::check(positive(speed_threshold_m_s), ctx + ".speed_threshold_m_s", "must be > 0");
  config::check(positive(action_tolerance_m), ctx + ".action_tolerance_m", "must be > 0");
  config::check(positive(action_speed_threshold_m_s), ctx + ".action_speed_threshold_m_s",
                "must be > 0");
  config::check(positive(initial_timeout_s), ctx + ".initial_timeout_s", "must be > 0");
  config::check(positive(transition_timeout_s), ctx + ".transition_timeout_s", "must be > 0");
  config::check(positive(final_timeout_s), ctx + ".final_timeout_s", "must be > 0");
  config::check(positive(state_timeout_s), ctx + ".state_timeout_s", "must be > 0");
  config::check(positive(imu_timeout_s), ctx + ".imu_timeout_s", "must be > 0");
  config::check(std::isfinite(imu_hold_s) && imu_hold_s >= 0.0 && imu_hold_s <= 1.0,
                ctx + ".imu_hold_s", "must be in [0, 1]");
  config::check(positive(emergency_hover_s) && emergency_hover_s <= 30.0,
                ctx + ".emergency_hover_s", "must be in (0, 30]");
  config::check(positive(emergency_descent_rate_m_s) && emergency_descent_rate_m_s <= 1.0,
                ctx + ".emergency_descent_rate_m_s", "must be in (0, 1]");
  config::check(positive(emergency_level_gain_1_s) && emergency_level_gain_1_s <= 20.0,
                ctx + ".emergency_level_gain_1_s", "must be in (0, 20]");
  config::check(positive(emergency_height_gain_1_s2) && emergency_height_gain_1_s2 <= 20.0,
                ctx + ".emergency_height_gain_1_s2", "must be in (0, 20]");
  config::check(positive(emergency_speed_gain_1_s) && emergency_speed_gain_1_s <= 20.0,
                ctx + ".emergency_speed_gain_1_s", "must be in (0, 20]");
  config::check(std::isfinite(emergency_integral_gain_1_s3) &&
                    emergency_integral_gain_1_s3 >= 0.0 && emergency_integral_gain_1_s3 <= 10.0,
                ctx + ".emergency_integral_gain_1_s3", "must be in [0, 10] (0 disables)");
  config::check(std::isfinite(emergency_integral_limit_m_s2) &&
                    emergency_integral_limit_m_s2 >= 0.0 && emergency_integral_limit_m_s2 <= 5.0,
                ctx + ".emergency_integral_limit_m_s2", "must be in [0, 5]");
  config::check(std::isfinite(emergency_blind_floor_m) && emergency_blind_floor_m >= 0.0 &&
                    emergency_blind_floor_m <= 10.0,
                ctx + ".emergency_blind_floor_m", "must be in [0, 10]");
  config::check(max_plan_attempts >= 1 && max_plan_attempts <= 1000, ctx + ".max_plan_attempts",
                "must be in [1, 1000]");
  config::check(plan_adopt_steps >= 0 && plan_adopt_steps <= 100, ctx + ".plan_adopt_steps",
                "must be in [0, 100]");
  config::check(
      std::isfinite(integral_gain_1_s3) && integral_gain_1_s3 >= 0.0 && integral_gain_1_s3 <= 20.0,
      ctx + ".integral_gain_1_s3", "must be in [0, 20] (0 disables)");
  config::check(
      std::isfinite(observer_window_s) && observer_window_s >= 0.0 && observer_window_s <= 5.0,
      ctx + ".observer_window_s", "must be in [0, 5] (0 disables)");
  config::check(std::isfinite(observer_time_constant_s) && observer_time_constant_s >= 0.1 &&
                    observer_time_constant_s <= 20.0,
                ctx + ".observer_time_constant_s", "must be in [0.1, 20]");
  config::check(positive(integral_error_clip_m), ctx + ".integral_error_clip_m", "must be > 0");
  config::check(positive(integral_limit_m_s2) && integral_limit_m_s2 <= 10.0,
                ctx + ".integral_limit_m_s2", "must be in (0, 10]");
  config::check(std::isfinite(abort_hold_s) && abort_hold_s >= 0.0, ctx + ".abort_hold_s",
                "must be >= 0");
  config::check(positive(abort_descent_rate_m_s) && abort_descent_rate_m_s <= 2.0,
                ctx + ".abort_descent_rate_m_s", "must be in (0, 2]");
  config::check(positive(land_detect_gap_m), ctx + ".land_detect_gap_m", "must be > 0");
  config::check(positive(land_detect_speed_m_s), ctx + ".land_detect_speed_m_s", "must be > 0");
  config::check(positive(land_detect_time_s), ctx + ".land_detect_time_s", "must be > 0");
  config::check(positive(approach_brake_fraction) && approach_brake_fraction <= 1.0,
                ctx + ".approach_brake_fraction", "must be in (0, 1]");
  config::check(std::isfinite(approach_speed_up_ramp_s) && approach_speed_up_ramp_s >= 0.0 &&
                    approach_speed_up_ramp_s <= 5.0,
                ctx + ".approach_speed_up_ramp_s", "must be in [0, 5]");
  config::check(std::isfinite(final_start_acceleration_fraction) &&
                    final_start_acceleration_fraction >= 0.0 &&
                    final_start_acceleration_fraction <= 1.0,
                ctx + ".final_start_acceleration_fraction", "must be in [0, 1]");
  config::check(positive(control_period_s) && control_period_s <= 0.1, ctx + ".control_period_s",
                "must be in (0, 0.1]");
}

void check_control_period(const MissionParams& mission, double other_period_s,
                          const std::string& other) {
  // Equal to a nanosecond: both are written as decimals of the same period (0.01 s, 100 Hz).
  if (std::abs(other_period_s - mission.control_period_s) <= 1e-9) return;
  throw config::ConfigError(other + " (" + config::format_number(other_period_s) +
                            " s) disagrees with " + kMissionControlPeriodKey + " (" +
                            config::format_number(mission.control_period_s) +
                            " s): the control period is one; set them equal");
}

}  // namespace cover::mission

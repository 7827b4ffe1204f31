#include "cover/sim/closed_loop_report.hpp"

#include <cmath>

namespace cover::sim {

std::optional<sampc::Mode> parse_method(const std::string& name) {
  return sampc::parse_mode(name);
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json summary_json(const ClosedLoopResult& r) {
  nlohmann::json tracking = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) tracking.push_back(number_or_null(r.final_tracking_error_m[i]));
  const double ratio = r.total_straight_length_m > 0.0
                           ? r.total_path_length_m / r.total_straight_length_m
                           : std::nan("");
  return {{"success", r.success},
          {"status", r.status},
          {"landing_error_m", number_or_null(r.landing_error_m)},
          {"delivery_error_m", number_or_null(r.delivery_error_m)},
          {"tracking_error_m", tracking},
          {"duration_s", r.duration_s},
          {"realtime_factor", r.realtime_factor},
          {"transitions", r.transitions.size()},
          {"Lt", r.total_path_length_m},
          {"Ls", r.total_straight_length_m},
          {"ratio", number_or_null(ratio)},
          {"mpc_median_us", r.mpc_median_us},
          {"mpc_p99_us", r.mpc_p99_us},
          {"plan_median_ms", r.plan_median_ms},
          {"plan_max_ms", r.plan_max_ms},
          {"failsafe_steps", r.failsafe_steps}};
}

std::string with_suffix(const std::string& path, const std::string& suffix) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return path + "_" + suffix;
  }
  return path.substr(0, dot) + "_" + suffix + path.substr(dot);
}

}  // namespace cover::sim

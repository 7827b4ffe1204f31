#include "cover/sim/closed_loop_report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

namespace cover::sim {

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
          {"eq30_law_ratio",
           number_or_null(r.eq30_law_straight_length_m > 0.0
                              ? r.eq30_law_path_length_m / r.eq30_law_straight_length_m
                              : std::nan(""))},
          {"bound_ratio", number_or_null(r.bound_straight_length_m > 0.0
                                             ? r.bound_path_length_m / r.bound_straight_length_m
                                             : std::nan(""))},
          {"mpc_median_us", number_or_null(r.mpc_median_us)},
          {"mpc_p99_us", number_or_null(r.mpc_p99_us)},
          {"mpc_cpu_median_us", number_or_null(r.mpc_cpu_median_us)},
          {"mpc_cpu_p99_us", number_or_null(r.mpc_cpu_p99_us)},
          {"command_median_us", number_or_null(r.command_median_us)},
          {"command_p99_us", number_or_null(r.command_p99_us)},
          {"plan_median_ms", number_or_null(r.plan_median_ms)},
          {"plan_max_ms", number_or_null(r.plan_max_ms)},
          {"step_median_us", number_or_null(r.step_median_us)},
          {"step_p99_us", number_or_null(r.step_p99_us)},
          {"step_max_us", number_or_null(r.step_max_us)},
          {"plan_wait_max_ms", number_or_null(r.plan_wait_max_ms)},
          {"failsafe_steps", r.failsafe_steps}};
}

namespace {

// A figure of the summary, printf-formatted, or "not measured".
std::string figure(const char* format, double value) {
  if (!std::isfinite(value)) return "not measured";
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

std::string readable_summary(const ClosedLoopResult& r) {
  auto cm = [](double m) { return m * 100.0; };
  std::string text;
  char line[512];
  auto add = [&](const char* format, auto... values) {
    std::snprintf(line, sizeof line, format, values...);
    text += line;
  };
  add("  result            %s\n", r.success ? "SUCCESS" : "FAILED");
  add("  status            %s\n", r.status.c_str());
  // NaN: the task has no landing or delivery, or it did not happen.
  auto error_line = [&](const char* label, double error_m) {
    if (std::isfinite(error_m)) {
      add("  %-17s %.1f cm (horizontal, on the deck)\n", label, cm(error_m));
    } else {
      add("  %-17s not measured (none in the task, or it did not happen)\n", label);
    }
  };
  error_line("landing error", r.landing_error_m);
  error_line("delivery error", r.delivery_error_m);
  if (r.final_tracking_samples > 0) {
    add("  final tracking    x %.1f  y %.1f  z %.1f cm (mean |error|, %d samples)\n",
        cm(r.final_tracking_error_m.x()), cm(r.final_tracking_error_m.y()),
        cm(r.final_tracking_error_m.z()), r.final_tracking_samples);
  } else {
    add("  final tracking    not measured (no final stage ran)\n");
  }
  add("  transitions       %zu, Lt/Ls %s\n", r.transitions.size(),
      figure("%.3f", r.total_straight_length_m > 0
                         ? r.total_path_length_m / r.total_straight_length_m
                         : std::nan(""))
          .c_str());
  add("  task duration     %.1f s simulated, %.2f s wall, %.0fx real time\n", r.duration_s,
      r.wall_time_s, r.realtime_factor);
  add("  MPC step          median %s, p99 %s (thread CPU %s / %s); stage plan median %s\n",
      figure("%.0f us", r.mpc_median_us).c_str(), figure("%.0f us", r.mpc_p99_us).c_str(),
      figure("%.0f us", r.mpc_cpu_median_us).c_str(), figure("%.0f us", r.mpc_cpu_p99_us).c_str(),
      figure("%.1f ms", r.plan_median_ms).c_str());
  add("  measurement->cmd  median %s, p99 %s (wall: inputs taken to command out)\n",
      figure("%.1f us", r.command_median_us).c_str(), figure("%.1f us", r.command_p99_us).c_str());
  if (std::isfinite(r.step_median_us)) {
    add("  control step      median %.0f us, p99 %.0f us, max %.0f us (wall, whole step); "
        "longest wait for a plan %s\n",
        r.step_median_us, r.step_p99_us, r.step_max_us,
        figure("%.2f ms", r.plan_wait_max_ms).c_str());
  } else {
    add("  control step      not measured here (the UAV agent runs it)\n");
  }
  return text;
}

std::string with_suffix(const std::string& path, const std::string& suffix) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) {
    return path + "_" + suffix;
  }
  return path.substr(0, dot) + "_" + suffix + path.substr(dot);
}

// One line per control step: time, stage, frame, the true relative position and velocity,
// the reference position, the command and the disturbance estimate (what a tracking error
// over time is read from).
bool write_step_trace(const ClosedLoopResult& r, const std::string& path) {
  std::ofstream out(path);
  if (!out) return false;
  out << "time_s,stage,process,reference_ugv,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,ref_x_m,ref_y_m,"
         "ref_z_m,thrust_m_s2,wx_rad_s,wy_rad_s,wz_rad_s,dx_m_s2,dy_m_s2,dz_m_s2\n";
  const auto row = [&out](const Eigen::Vector3d& v) {
    out << ',' << v.x() << ',' << v.y() << ',' << v.z();
  };
  for (const StepSample& s : r.step_trace) {
    out << s.time_s << ',' << s.stage_code << ',' << s.process_index << ',' << s.reference_ugv;
    row(s.position_m);
    row(s.velocity_m_s);
    row(s.reference_position_m);
    out << ',' << s.thrust_m_s2;
    row(s.body_rate_rad_s);
    row(s.disturbance_m_s2);
    out << '\n';
  }
  return static_cast<bool>(out);
}

}  // namespace cover::sim

// cover-bench stability: the paper's Fig. 8. One G0 -> G1 transition per UGV motion pattern
// and method; how abruptly the commands change at the frame switch (body-rate and thrust
// change per control step in a window after it) and how fast the UAV flies in the world.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/vocabulary/angles.hpp"
#include "not_measured.hpp"

namespace {

using cover::sim::MotionPatternKind;

struct Row {
  std::string pattern;
  std::string method;
  bool switched = false;  // a transition stage started (the frame switched)
  cover::sim::TransitionRecord transition;
  std::string status;
};

// Fig. 8's UGV motions (docs/model.md): circle (0.5 m/s, 0.5 rad/s); figure-eight and star at
// a peak speed of 0.8 m/s. Both UGVs drive the same pattern around centres 6 m apart.
void set_pattern(cover::sim::Scenario& scenario, const std::string& pattern) {
  const double centre_x[] = {-3.0, 3.0};
  for (std::size_t k = 0; k < scenario.world.ugvs.size() && k < 2; ++k) {
    cover::sim::UgvMotionPatternParams& p = scenario.world.ugvs[k].pattern;
    p.origin_m = Eigen::Vector2d(centre_x[k], 0.0);
    p.phase_rad = k == 0 ? 0.0 : cover::model::kPi / 2.0;
    if (pattern == "circle") {
      p.kind = MotionPatternKind::Circle;
      p.speed_m_s = 0.5;
      p.yaw_rate_rad_s = 0.5;
    } else if (pattern == "eight") {
      p.kind = MotionPatternKind::FigureEight;
      p.speed_m_s = 0.8;
      p.half_length_m = 2.0;
      p.half_width_m = 1.0;
    } else {
      p.kind = MotionPatternKind::Star;
      p.speed_m_s = 0.8;
      p.radius_m = 2.0;
      p.star_points = 5;
      p.star_depth = 0.2;
    }
  }
}

cover::sim::Scenario fig8_scenario(const std::string& pattern) {
  cover::sim::Scenario scenario =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("table1"));
  scenario.name = "fig8-" + pattern;
  scenario.task = cover::mission::repeat_processes(scenario.task, 1);  // G0 -> G1 only
  scenario.max_duration_s = 60.0;
  set_pattern(scenario, pattern);
  scenario.validate();
  return scenario;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("Fig. 8: command smoothness at the frame switch (2 s window after it)\n");
  std::printf("%-8s %-11s %14s %14s %14s %12s\n", "pattern", "method", "peak dw rad/s",
              "rms dw rad/s", "peak dF m/s2", "peak v m/s");
  for (const Row& r : rows) {
    if (!r.switched) {
      std::printf("%-8s %-11s  no frame switch: %s\n", r.pattern.c_str(), r.method.c_str(),
                  r.status.c_str());
      continue;
    }
    std::printf("%-8s %-11s %14.3f %14.3f %14.3f %12.2f\n", r.pattern.c_str(), r.method.c_str(),
                r.transition.peak_rate_change_rad_s, r.transition.rms_rate_change_rad_s,
                r.transition.peak_thrust_change_m_s2, r.transition.peak_world_speed_m_s);
  }
  std::printf("dw: body-rate command change per 10 ms control step; dF: thrust change.\n");
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"Fig. 8: command change at the frame switch, per UGV pattern and method"};
  bool json = false;
  std::string pattern;
  std::uint64_t seed = 0;
  std::string plot_file;
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--pattern", pattern, "circle | eight | star (default: all three)")
      ->check(CLI::IsMember({"circle", "eight", "star"}));
  app.add_option("--seed", seed, "world seed (default: the scenario file's)");
  CLI::Option* plot = app.add_option(
      "--plot", plot_file,
      "SVG of the first pattern's cover run (default stability.svg); baselines get _<method>");
  plot->expected(0, 1);
  std::string trace_file;
  app.add_option("--trace", trace_file,
                 "CSV of every control step of the first pattern's cover run; baselines get "
                 "_<method>");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  std::vector<std::string> patterns = {"circle", "eight", "star"};
  if (!pattern.empty()) patterns = {pattern};
  if (plot->count() > 0 && plot_file.empty()) plot_file = "stability.svg";

  std::vector<Row> rows;
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    for (const cover::sampc::Mode mode : cover::bench::baseline_first_modes()) {
      const std::string method = cover::sampc::to_string(mode);
      cover::sim::Scenario scenario = fig8_scenario(patterns[i]);
      if (app.count("--seed") > 0) scenario.world.seed = seed;
      const auto config = cover::uav::ControllerConfig::load_default(mode);
      cover::sim::ClosedLoopOptions options;
      options.record_paths = plot->count() > 0 && i == 0;
      options.record_step_trace = !trace_file.empty() && i == 0;
      const cover::sim::ClosedLoop loop(scenario, config, options);
      const cover::sim::ClosedLoopResult result = loop.run();
      Row row;
      row.pattern = patterns[i];
      row.method = method;
      row.switched = !result.transitions.empty();
      row.status = result.status;
      if (row.switched) row.transition = result.transitions.front();
      if (options.record_paths) {
        const std::string file = mode == cover::sampc::Mode::Cover
                                     ? plot_file
                                     : cover::sim::with_suffix(plot_file, method);
        const std::string title = "Fig. 8, " + patterns[i] + ": " + method;
        if (!cover::sim::write_path_plot(result, scenario, title, file)) {
          std::cerr << "cannot write " << file << "\n";
          return 1;
        }
      }
      if (options.record_step_trace) {
        const std::string file = mode == cover::sampc::Mode::Cover
                                     ? trace_file
                                     : cover::sim::with_suffix(trace_file, method);
        if (!cover::sim::write_step_trace(result, file)) {
          std::cerr << "cannot write " << file << "\n";
          return 1;
        }
      }
      rows.push_back(row);
    }
  }

  cover::bench::NotMeasured missing;
  for (const Row& r : rows) {
    if (!r.switched) {
      missing.add(r.pattern + ", " + r.method + ": the frame never switched (" + r.status + ")");
    }
  }
  if (json) {
    nlohmann::json out;
    out["window_s"] = cover::sim::ClosedLoopOptions{}.switch_window_s;
    out["rows"] = nlohmann::json::array();
    for (const Row& r : rows) {
      const auto value = [&](double v) {
        return r.switched ? cover::sim::number_or_null(v) : nlohmann::json(nullptr);
      };
      out["rows"].push_back({{"pattern", r.pattern},
                             {"method", r.method},
                             {"peak_rate_change", value(r.transition.peak_rate_change_rad_s)},
                             {"rms_rate_change", value(r.transition.rms_rate_change_rad_s)},
                             {"peak_thrust_change", value(r.transition.peak_thrust_change_m_s2)},
                             {"peak_world_speed", value(r.transition.peak_world_speed_m_s)},
                             {"status", r.status}});
    }
    if (plot->count() > 0) out["plot"] = plot_file;
    std::cout << out.dump(2) << "\n";
  } else {
    print_table(rows);
    if (plot->count() > 0) std::printf("plot: %s (baselines: _<method>)\n", plot_file.c_str());
  }
  return missing.exit_code("stability");
}

const cover::bench::Registrar registrar{
    "stability", "paper Fig. 8: command change at the frame switch per pattern", &run};

}  // namespace

// cover-bench sim: cost of one physics step of the world-frame simulator (RK4 plant,
// contact, UGV patterns, relative sensor and IMU + filter) on the shipped worlds, and an
// optional top-view SVG of each world's UGV paths.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/svg_plot.hpp"
#include "cover/sim/world.hpp"

namespace {

const char* const kWorlds[] = {"world_default", "world_figure_eight", "world_star",
                               "world_s_curve", "world_lines",        "world_three_circles"};

using cover::bench::percentile;

struct WorldTiming {
  std::string name;
  int ugvs = 0;
  double median_us = 0.0;
  double p99_us = 0.0;
  double real_time_factor = 0.0;  // simulated seconds per wall-clock second
};

// Lifts off and flies a slow climbing turn, so the plant, the contact check and every
// sensor do their full work on each step.
cover::sim::QuadrotorCommand climbing_turn(const cover::sim::World& world) {
  cover::sim::QuadrotorCommand command;
  command.thrust_m_s2 = 1.1 * world.hover_thrust_command_m_s2();
  command.body_rate_rad_s = cover::sim::Vec3(0.05, -0.05, 0.3);
  return command;
}

WorldTiming time_world(const std::string& name, const cover::sim::WorldParams& params, int steps) {
  using Clock = std::chrono::steady_clock;
  cover::sim::World world(params);
  const auto command = climbing_turn(world);
  std::vector<double> step_us;
  step_us.reserve(static_cast<std::size_t>(steps));
  const auto start = Clock::now();
  for (int i = 0; i < steps; ++i) {
    const auto before = Clock::now();
    world.step(command);
    step_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - before).count());
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  return {name, world.ugv_count(), percentile(step_us, 0.5), percentile(step_us, 0.99),
          steps * world.physics_dt_s() / wall_s};
}

bool write_ugv_plot(const std::string& name, const cover::sim::WorldParams& params,
                    const std::string& path, double duration_s) {
  cover::sim::SvgPlot plot("UGV paths: " + name + " (" + std::to_string(int(duration_s)) + " s)");
  for (std::size_t k = 0; k < params.ugvs.size(); ++k) {
    const cover::sim::UgvMotionPattern pattern(params.ugvs[k].pattern);
    std::vector<Eigen::Vector2d> points;
    for (double t = 0.0; t <= duration_s; t += 0.05) points.push_back(pattern.at(t).position_m);
    plot.add_ugv_path(points, static_cast<int>(k),
                      params.ugvs[k].name + " (" + to_string(params.ugvs[k].pattern.kind) + ")");
    plot.add_marker(points.front(), params.ugvs[k].name + " start");
  }
  return plot.write_file(path);
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"World simulator: time per 1 kHz physics step on the shipped worlds"};
  bool json = false;
  int steps = 20000;
  std::string svg_dir;
  app.add_flag("--json", json, "print JSON");
  app.add_option("--steps", steps, "physics steps per world (>= 100)")
      ->check(CLI::Range(100, 10000000));
  app.add_option("--svg-dir", svg_dir, "also write <dir>/<world>_ugvs.svg (UGV paths, 60 s)");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  std::vector<WorldTiming> timings;
  for (const char* name : kWorlds) {
    const auto params = cover::sim::WorldParams::load_file(cover::config::default_config_dir() +
                                                           "/sim/" + name + ".yaml");
    timings.push_back(time_world(name, params, steps));
    if (!svg_dir.empty() &&
        !write_ugv_plot(name, params, svg_dir + "/" + name + "_ugvs.svg", 60.0)) {
      std::cerr << "cover-bench sim: cannot write into " << svg_dir << "\n";
      return 1;
    }
  }

  if (json) {
    nlohmann::json out;
    out["steps_per_world"] = steps;
    for (const auto& t : timings) {
      out["worlds"].push_back({{"name", t.name},
                               {"ugvs", t.ugvs},
                               {"step_median_us", t.median_us},
                               {"step_p99_us", t.p99_us},
                               {"real_time_factor", t.real_time_factor}});
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("World simulator, %d physics steps (1 kHz) per world\n", steps);
  std::printf("%-22s %5s %14s %12s %16s\n", "world", "UGVs", "median [us]", "p99 [us]",
              "x real time");
  for (const auto& t : timings) {
    std::printf("%-22s %5d %14.2f %12.2f %16.0f\n", t.name.c_str(), t.ugvs, t.median_us, t.p99_us,
                t.real_time_factor);
  }
  return 0;
}

const cover::bench::Registrar registrar{"sim", "world simulator: time per physics step", &run};

}  // namespace

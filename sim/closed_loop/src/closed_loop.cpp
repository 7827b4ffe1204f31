#include "cover/sim/closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "cover/config/format_number.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/sim/percentile.hpp"
#include "cover/sim/run_recorder.hpp"
#include "cover/sim/svg_plot.hpp"
#include "cover/sim/world.hpp"
#include "cover/sim/world_uav_io.hpp"
#include "cover/uav/uav_loop.hpp"

namespace cover::sim {

ClosedLoop::ClosedLoop(Scenario scenario, uav::ControllerConfig config, ClosedLoopOptions options)
    : scenario_(std::move(scenario)), config_(std::move(config)), options_(options) {
  scenario_.validate();
  config_.validate();
  const double ratio = scenario_.world.physics_rate_hz / options_.control_rate_hz;
  config::check(options_.control_rate_hz > 0.0 && std::abs(ratio - std::round(ratio)) < 1e-9,
                "closed_loop.control_rate_hz", "must divide the physics rate");
  mission::check_control_period(
      config_.mission, 1.0 / options_.control_rate_hz,
      "closed_loop.control_rate_hz " + config::format_number(options_.control_rate_hz) + " Hz");
  config::check(options_.record_every_control_steps >= 1, "closed_loop.record_every_control_steps",
                "must be >= 1");
}

ClosedLoopResult ClosedLoop::run() const {
  const auto wall_start = std::chrono::steady_clock::now();
  World world(scenario_.world);
  uav::UavLoop loop(static_cast<std::uint32_t>(scenario_.task.uav_id), world.ugv_count(), config_);
  const uav::TaskDecision decision = loop.give_task(scenario_.task);
  if (!decision.accepted) throw config::ConfigError(scenario_.name + ": " + decision.reason);
  const int physics_per_control =
      static_cast<int>(std::lround(scenario_.world.physics_rate_hz / options_.control_rate_hz));

  RunRecorder recorder(scenario_, scenario_.task, config_.mission, options_);
  WorldUavInputs inputs(world);
  PlantCommandOutput plant;
  std::vector<double> step_us;
  step_us.reserve(static_cast<std::size_t>(scenario_.max_duration_s * options_.control_rate_hz) +
                  1);
  double plan_wait_max_ms = 0.0;
  while (!recorder.finished(world.state().time_s)) {
    const auto step_start = std::chrono::steady_clock::now();
    const mission::ControllerOutput& out = loop.step(world.state().time_s, inputs, plant);
    step_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - step_start)
            .count());
    if (out.status.planned) plan_wait_max_ms = std::max(plan_wait_max_ms, out.status.plan_wait_ms);
    if (out.command.release_payload && world.release_payload()) recorder.record_release(world);
    recorder.record(out.status, out.command, world);
    for (int i = 0; i < physics_per_control; ++i) world.step(plant.command());
  }

  ClosedLoopResult result =
      recorder.finish(world, loop.output().status, loop.describe(), loop.task_state());
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.step_median_us = percentile(step_us, 0.5);
  result.step_p99_us = percentile(step_us, 0.99);
  result.step_max_us = percentile(step_us, 1.0);
  result.plan_wait_max_ms = plan_wait_max_ms;
  result.realtime_factor =
      result.wall_time_s > 0.0 ? world.state().time_s / result.wall_time_s : 0.0;
  if (options_.transition_bounds) recorder.add_transition_bounds(result);
  return result;
}

bool write_path_plot(const ClosedLoopResult& result, const Scenario& scenario,
                     const std::string& title, const std::string& path) {
  SvgPlot plot(title);
  for (std::size_t k = 0; k < result.ugv_paths.size(); ++k) {
    const std::string name =
        k < scenario.world.ugvs.size() ? scenario.world.ugvs[k].name : "G" + std::to_string(k);
    plot.add_ugv_path(result.ugv_paths[k], static_cast<int>(k), name + " path");
  }
  std::vector<Eigen::Vector2d> points;
  std::vector<int> stages;
  for (const StagedPoint& p : result.uav_path) {
    points.push_back(p.uav_world_m);
    stages.push_back(p.stage_code);
  }
  plot.add_staged_path_codes(points, stages);
  bool first = true;
  for (const TransitionRecord& r : result.transitions) {
    SvgStyle style{"#d62728", 1.0, true, first ? "shortest transition path (L_s)" : ""};
    plot.add_path({r.start_world_m.head<2>(), r.end_world_m.head<2>()}, style);
    first = false;
  }
  for (const auto& p : result.release_points) plot.add_marker(p, "release");
  for (const auto& p : result.landing_points) plot.add_marker(p, "landing", "#9467bd");
  return plot.write_file(path);
}

}  // namespace cover::sim

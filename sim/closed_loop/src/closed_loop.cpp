#include "cover/sim/closed_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "cover/config/yaml_reader.hpp"
#include "cover/sim/svg_plot.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim {
namespace {

using model::Stage;

double percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

mission::RelativeMeasurement to_measurement(const RelativeState& state) {
  mission::RelativeMeasurement m;
  m.stamp_s = state.stamp_s;
  m.position_m = state.position_m;
  m.velocity_m_s = state.velocity_m_s;
  m.attitude = state.attitude;
  return m;
}

mission::UgvImuMeasurement to_measurement(const ugv::FilteredImu& imu) {
  mission::UgvImuMeasurement m;
  m.stamp_s = imu.stamp_s;
  m.motion.specific_force_m_s2 = imu.specific_force_m_s2;
  m.motion.angular_velocity_rad_s = imu.angular_velocity_rad_s;
  m.motion.angular_acceleration_rad_s2 = imu.angular_acceleration_rad_s2;
  return m;
}

// Follows the transition stages of a run and measures them in the world frame.
class TransitionTracker {
 public:
  explicit TransitionTracker(double window_s) : window_s_(window_s) {}

  void update(const mission::ControllerStatus& status, const mission::ControlCommand& command,
              const WorldState& world, std::vector<TransitionRecord>& records) {
    const Eigen::Vector3d position = world.uav.position_m.eigen();
    const bool in_transition = status.stage.state == mission::MissionState::Running &&
                               status.stage.stage == Stage::Transition;
    const bool same =
        open_ && records.back().process_index == static_cast<int>(status.stage.process_index);
    if (open_ && !(in_transition && same)) close(world, status, records);
    if (in_transition && !open_) open(status, world, records);
    if (open_) {
      TransitionRecord& r = records.back();
      r.path_length_m += (position - last_position_).norm();
      if (world.time_s - r.start_time_s <= window_s_) {
        const double rate_change = (command.body_rate_rad_s - last_rates_).norm();
        r.peak_rate_change_rad_s = std::max(r.peak_rate_change_rad_s, rate_change);
        rate_change_square_sum_ += rate_change * rate_change;
        ++window_steps_;
        r.rms_rate_change_rad_s = std::sqrt(rate_change_square_sum_ / window_steps_);
        r.peak_thrust_change_m_s2 =
            std::max(r.peak_thrust_change_m_s2, std::abs(command.thrust_m_s2 - last_thrust_));
        r.peak_world_speed_m_s =
            std::max(r.peak_world_speed_m_s, world.uav.velocity_m_s.eigen().norm());
      }
    }
    last_position_ = position;
    last_rates_ = command.body_rate_rad_s;
    last_thrust_ = command.thrust_m_s2;
  }

  void finish(const WorldState& world, const mission::ControllerStatus& status,
              std::vector<TransitionRecord>& records) {
    if (open_) close(world, status, records);
  }

 private:
  void open(const mission::ControllerStatus& status, const WorldState& world,
            std::vector<TransitionRecord>& records) {
    TransitionRecord r;
    r.process_index = static_cast<int>(status.stage.process_index);
    r.start_time_s = world.time_s;
    // The stage started with the last measured position: the path starts where the UAV was.
    r.start_world_m = last_position_;
    r.start_world_velocity_m_s = world.uav.velocity_m_s.eigen();
    records.push_back(r);
    open_ = true;
    rate_change_square_sum_ = 0.0;
    window_steps_ = 0;
  }

  void close(const WorldState& world, const mission::ControllerStatus& status,
             std::vector<TransitionRecord>& records) {
    TransitionRecord& r = records.back();
    r.end_time_s = world.time_s;
    r.end_world_m = world.uav.position_m.eigen();
    r.straight_length_m = (r.end_world_m - r.start_world_m).norm();
    // It ended by reaching its point iff the machine moved on (not failed, not cut off).
    r.completed = status.stage.state != mission::MissionState::Failed &&
                  !(status.stage.stage == Stage::Transition &&
                    static_cast<int>(status.stage.process_index) == r.process_index);
    open_ = false;
  }

  double window_s_;
  bool open_ = false;
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_rates_ = Eigen::Vector3d::Zero();
  double last_thrust_ = 0.0;
  double rate_change_square_sum_ = 0.0;
  int window_steps_ = 0;
};

void fill_action_errors(const Scenario& scenario, const World& world, ClosedLoopResult& result) {
  const WorldState& ws = world.state();
  for (const mission::TransitionProcess& p : scenario.task.processes) {
    if (p.final_action == mission::FinalAction::Deliver && ws.payload.released &&
        std::isnan(result.delivery_error_m)) {
      const Eigen::Vector3d at = ws.payload.release_position_in_ugv_m[p.to_ugv].eigen();
      result.delivery_error_m = (at - p.final_point_m).head<2>().norm();
    }
  }
  const mission::TransitionProcess& last = scenario.task.processes.back();
  if (last.final_action == mission::FinalAction::Land &&
      result.mission_state == mission::MissionState::Complete) {
    const RelativeState on_deck = world.true_relative_state(last.to_ugv);
    result.landing_error_m = (on_deck.position_m - last.final_point_m).head<2>().norm();
    result.landed_on_target_deck = ws.uav_contact.resting && ws.uav_contact.surface == last.to_ugv;
    result.landing_points.push_back(ws.uav.position_m.eigen().head<2>());
  }
}

// Flies every completed transition's start again with the eq. 30 law (approach_law.hpp).
void fill_eq30_law_transitions(const Scenario& scenario, const mission::MissionParams& mission,
                               ClosedLoopResult& result) {
  for (TransitionRecord& r : result.transitions) {
    if (!r.completed) continue;
    const mission::TransitionProcess& process = scenario.task.processes[r.process_index];
    ApproachLawParams law;
    law.vmax_m_s = process.vmax_m_s;
    law.amax_m_s2 = process.amax_m_s2;
    law.reach_tolerance_m = mission.transition_reach_tolerance_m;
    law.speed_threshold_m_s = mission.speed_threshold_m_s;
    const UgvMotionPattern target(scenario.world.ugvs[process.to_ugv].pattern);
    r.eq30_law = fly_approach_law(target, r.start_time_s, r.start_world_m.head<2>(),
                                  r.start_world_velocity_m_s.head<2>(), law);
    result.eq30_law_path_length_m += r.eq30_law.path_length_m;
    result.eq30_law_straight_length_m += r.eq30_law.straight_length_m;
  }
}

bool task_succeeded(const Scenario& scenario, const World& world, const ClosedLoopResult& r) {
  if (r.mission_state != mission::MissionState::Complete) return false;
  for (const auto& p : scenario.task.processes) {
    if (p.final_action == mission::FinalAction::Deliver && !world.state().payload.released) {
      return false;
    }
  }
  const auto& last = scenario.task.processes.back();
  return last.final_action != mission::FinalAction::Land || r.landed_on_target_deck;
}

}  // namespace

ClosedLoop::ClosedLoop(Scenario scenario, mission::MissionParams mission,
                       planner::PlannerParams planner, sampc::SampcParams sampc,
                       ClosedLoopOptions options)
    : scenario_(std::move(scenario)),
      mission_(mission),
      planner_(std::move(planner)),
      sampc_(sampc),
      options_(options) {
  scenario_.validate();
  mission_.validate();
  planner_.validate();
  sampc_.validate();
  const double ratio = scenario_.world.physics_rate_hz / options_.control_rate_hz;
  config::check(options_.control_rate_hz > 0.0 && std::abs(ratio - std::round(ratio)) < 1e-9,
                "closed_loop.control_rate_hz", "must divide the physics rate");
  config::check(options_.record_every_control_steps >= 1, "closed_loop.record_every_control_steps",
                "must be >= 1");
}

ClosedLoopResult ClosedLoop::run() const {
  const auto wall_start = std::chrono::steady_clock::now();
  World world(scenario_.world);
  const int ugv_count = world.ugv_count();
  mission::MissionController controller(scenario_.task, ugv_count, mission_, planner_, sampc_);
  const int physics_per_control =
      static_cast<int>(std::lround(scenario_.world.physics_rate_hz / options_.control_rate_hz));

  ClosedLoopResult result;
  result.ugv_paths.resize(static_cast<std::size_t>(ugv_count));
  std::vector<double> mpc_us;
  std::vector<double> plan_ms;
  mpc_us.reserve(static_cast<std::size_t>(scenario_.max_duration_s * options_.control_rate_hz) + 1);
  TransitionTracker transitions(options_.switch_window_s);
  Eigen::Vector3d abs_error_sum = Eigen::Vector3d::Zero();
  double done_time_s = -1.0;
  QuadrotorCommand command;

  for (long step = 0;; ++step) {
    const WorldState& ws = world.state();
    const double t = ws.time_s;
    if (t > scenario_.max_duration_s + 1e-9) break;
    if (done_time_s >= 0.0 && t - done_time_s >= scenario_.settle_time_s) break;

    // Sensors -> controller: only what the real UAV would receive.
    for (int k = 0; k < ugv_count; ++k) {
      if (world.relative_sensor().has_measurement()) {
        controller.set_relative_state(k, to_measurement(world.relative_sensor().latest(k)));
      }
      if (world.imu_sensor().has_reading()) {
        controller.set_ugv_imu(k, to_measurement(world.imu_sensor().latest(k).filtered));
      }
    }
    const mission::ControllerOutput& out = controller.step(t);
    const mission::ControllerStatus& status = out.status;
    if (out.command.release_payload && world.release_payload()) {
      result.release_points.push_back(ws.payload.release_position_m.eigen().head<2>());
    }
    command.thrust_m_s2 = out.command.armed ? out.command.thrust_m_s2 : 0.0;
    command.body_rate_rad_s =
        Vec3(out.command.armed ? out.command.body_rate_rad_s : Eigen::Vector3d::Zero());

    // Metrics.
    transitions.update(status, out.command, ws, result.transitions);
    const bool running = status.stage.state == mission::MissionState::Running;
    if (running && status.stage.stage == Stage::Final &&
        status.failsafe == mission::Failsafe::None) {
      const RelativeState truth = world.true_relative_state(status.stage.reference_ugv);
      abs_error_sum += (truth.position_m - status.reference_position_m).cwiseAbs();
      ++result.final_tracking_samples;
    }
    if (status.solve_us > 0.0) mpc_us.push_back(status.solve_us);
    if (status.planned) plan_ms.push_back(status.plan_ms);
    if (status.failsafe == mission::Failsafe::StaleInput ||
        status.failsafe == mission::Failsafe::SolverError) {
      ++result.failsafe_steps;
    }
    if (options_.record_paths && step % options_.record_every_control_steps == 0) {
      const bool staged = status.stage.state != mission::MissionState::NotStarted;
      result.uav_path.push_back({ws.uav.position_m.eigen().head<2>(),
                                 staged ? static_cast<int>(status.stage.stage) : -1});
      for (int k = 0; k < ugv_count; ++k) {
        result.ugv_paths[k].push_back(ws.ugvs[k].position_m.eigen().head<2>());
      }
    }
    if (done_time_s < 0.0 && (status.stage.state == mission::MissionState::Complete ||
                              status.stage.state == mission::MissionState::Failed)) {
      done_time_s = t;
    }

    for (int i = 0; i < physics_per_control; ++i) world.step(command);
  }

  const mission::StageMachine& machine = controller.stage_machine();
  transitions.finish(world.state(), controller.output().status, result.transitions);
  result.mission_state = machine.decision().state;
  result.status = machine.describe();
  result.duration_s = done_time_s >= 0.0 ? done_time_s : world.state().time_s;
  for (const TransitionRecord& r : result.transitions) {
    if (!r.completed) continue;
    result.total_path_length_m += r.path_length_m;
    result.total_straight_length_m += r.straight_length_m;
  }
  for (TransitionRecord& r : result.transitions) {
    const auto& p = scenario_.task.processes[r.process_index];
    r.from_ugv = p.from_ugv;
    r.to_ugv = p.to_ugv;
  }
  if (result.final_tracking_samples > 0) {
    result.final_tracking_error_m = abs_error_sum / result.final_tracking_samples;
  }
  fill_action_errors(scenario_, world, result);
  fill_eq30_law_transitions(scenario_, mission_, result);
  result.success = task_succeeded(scenario_, world, result);
  result.mpc_median_us = percentile(mpc_us, 0.5);
  result.mpc_p99_us = percentile(mpc_us, 0.99);
  result.plan_median_ms = percentile(plan_ms, 0.5);
  result.plan_max_ms = plan_ms.empty() ? 0.0 : *std::max_element(plan_ms.begin(), plan_ms.end());
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.realtime_factor =
      result.wall_time_s > 0.0 ? world.state().time_s / result.wall_time_s : 0.0;
  return result;
}

ControllerConfig ControllerConfig::load_default(sampc::Mode mode) {
  const std::string dir = config::default_config_dir();
  ControllerConfig c;
  c.mission = mission::MissionParams::load_file(dir + "/mission.yaml");
  c.planner = planner::PlannerParams::load_file(dir + "/planner.yaml");
  c.sampc = sampc::SampcParams::load_file(dir + "/sampc.yaml");
  c.sampc.mode = mode;
  c.sampc.validate();
  return c;
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

#pragma once

#include <vector>

#include "cover/mission/mission_controller.hpp"
#include "cover/mission/mission_params.hpp"
#include "cover/sim/run_options.hpp"
#include "cover/sim/run_result.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/sim/world.hpp"

namespace cover::sim {

// Measures one UAV's run from ground truth: fed, every control step, what the controller
// reported and commanded and the world it acted in; produces the paper's metrics
// (transition path ratios, command changes at the switch, final tracking, landing and
// delivery errors). The in-process harness and cover-sim record with the same code.
class RunRecorder {
 public:
  // `task` is the task this UAV flies in `scenario`'s world.
  RunRecorder(const Scenario& scenario, const mission::Task& task,
              const mission::MissionParams& mission, const ClosedLoopOptions& options);

  // One control step at world time `world.state().time_s`, before the physics advance.
  void record(const mission::ControllerStatus& status, const mission::ControlCommand& command,
              const World& world);
  // The airdrop opened on this step (World::release_payload returned true).
  void record_release(const World& world);

  // True once the run should stop: the task ended `settle_time_s` ago, or time is up.
  bool finished(double time_s) const;
  // True once the controller reported the task complete or failed, or aborted and landed.
  bool task_ended() const { return done_time_s_ >= 0.0; }

  // The metrics. `status` and `state` are the controller's last words on the task.
  ClosedLoopResult finish(const World& world, const mission::ControllerStatus& last_status,
                          const std::string& status, mission::MissionState state);
  // Fills each completed transition's shortest-path bound (transition_bound.hpp) into
  // `result` (finish()'s). Apart from finish() because it costs some 30 ms per transition,
  // which must not count as the loop's wall time.
  void add_transition_bounds(ClosedLoopResult& result) const;

 private:
  void record_tracking(const mission::ControllerStatus& status, const World& world);
  void record_path(const mission::ControllerStatus& status, const WorldState& world);
  void record_step(const mission::ControllerStatus& status, const mission::ControlCommand& command,
                   const World& world);
  void fill_action_errors(const World& world);
  void fill_eq30_law_transitions();
  bool task_succeeded(const World& world) const;

  const Scenario& scenario_;
  const mission::Task& task_;
  mission::MissionParams mission_;
  ClosedLoopOptions options_;
  ClosedLoopResult result_;
  std::vector<double> mpc_us_;
  std::vector<double> mpc_cpu_us_;
  std::vector<double> command_us_;
  std::vector<double> plan_ms_;
  Eigen::Vector3d abs_error_sum_ = Eigen::Vector3d::Zero();
  double done_time_s_ = -1.0;
  long steps_ = 0;
  // Following the open transition stage (world-frame path, command changes).
  struct TrackerState {
    bool open = false;
    Eigen::Vector3d last_position = Eigen::Vector3d::Zero();
    Eigen::Vector3d last_rates = Eigen::Vector3d::Zero();
    double last_thrust = 0.0;
    double rate_change_square_sum = 0.0;
    int window_steps = 0;
  } tracker_;

  void track_transitions(const mission::ControllerStatus& status,
                         const mission::ControlCommand& command, const WorldState& world);
  void open_transition(const mission::ControllerStatus& status, const WorldState& world);
  void close_transition(const WorldState& world, const mission::ControllerStatus& status);
};

}  // namespace cover::sim

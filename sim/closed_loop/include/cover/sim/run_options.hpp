#pragma once

namespace cover::sim {

// How a run is stepped and recorded (the in-process harness and cover-sim alike).
struct ClosedLoopOptions {
  double control_rate_hz = 100.0;      // MissionController rate; must divide the physics rate
  double switch_window_s = 2.0;        // command-change statistics window after each frame switch
  bool record_paths = true;            // keep world-frame paths (for plots)
  int record_every_control_steps = 5;  // path decimation (5: 20 Hz points)
  // The in-process harness computes each completed transition's shortest-path bound after
  // the run (transition_bound.hpp, some 30 ms per transition, not in the wall time).
  bool transition_bounds = true;
  // Keep every control step's state, reference and command (ClosedLoopResult::step_trace).
  bool record_step_trace = false;
};

}  // namespace cover::sim

#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cover/sim/run_options.hpp"
#include "cover/sim/run_result.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/uav/controller_config.hpp"

namespace cover::sim {

// Runs a scenario in one process at fixed rates: the simulator World (physics 1 kHz,
// relative sensor, UGV IMU 200 Hz through the UGV IMU filter) and the UAV loop
// (uav::UavLoop, the agent's loop) at 100 Hz, fed the sensor outputs only. Deterministic
// for a world seed: same inputs, same result (except the wall-clock timings).
class ClosedLoop {
 public:
  // Throws config::ConfigError for invalid parameters or a rate mismatch.
  ClosedLoop(Scenario scenario, uav::ControllerConfig config, ClosedLoopOptions options = {});

  ClosedLoopResult run() const;

  const Scenario& scenario() const { return scenario_; }

 private:
  Scenario scenario_;
  uav::ControllerConfig config_;
  ClosedLoopOptions options_;
};

// Fig. 7-like top view: UGV paths in greys, the UAV path coloured by stage, transition
// start/end straight lines dashed, release and landing markers. False if not writable.
bool write_path_plot(const ClosedLoopResult& result, const Scenario& scenario,
                     const std::string& title, const std::string& path);

}  // namespace cover::sim

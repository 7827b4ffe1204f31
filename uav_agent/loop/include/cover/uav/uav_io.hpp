#pragma once

#include <cstdint>

#include "cover/mission/mission_controller.hpp"

namespace cover::uav {

// Where the UAV loop gets its measurements: the simulator's sensors in process, the
// latest DDS samples in the agent. Implementations return false when they have nothing
// (yet) for that UGV; the controller then treats the input as missing or stale.
class UavInputs {
 public:
  virtual ~UavInputs() = default;
  virtual bool relative_state(int ugv, mission::RelativeMeasurement& out) = 0;
  virtual bool ugv_imu(int ugv, mission::UgvImuMeasurement& out) = 0;
};

// One control step's result, as the loop hands it to its command output.
struct StepOutput {
  std::uint32_t uav_id = 0;
  double stamp_s = 0.0;              // the step's time
  double measurement_stamp_s = 0.0;  // stamp of the reference frame's relative state used
  const mission::ControllerOutput* output = nullptr;  // command and status (never null)
};

// Where the command goes: the simulated plant in process, the command and trace topics
// in the agent. Called once per step, always (a disarmed idle command when there is no
// task), so a lockstep simulator sees every tick answered.
class CommandOutput {
 public:
  virtual ~CommandOutput() = default;
  virtual void write(const StepOutput& step) = 0;
};

}  // namespace cover::uav

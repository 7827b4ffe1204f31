#pragma once

#include <cstdint>
#include <string>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/controller_output.hpp"

namespace cover::wire {

// One control step's command, stamped with the step time and the stamp of the relative
// state it was computed from (for sensor-to-command latency).
msg::UavCommand to_msg(const mission::ControlCommand& command, std::uint32_t uav_id, double stamp_s,
                       double measurement_stamp_s, std::uint32_t seq);
mission::ControlCommand from_msg(const msg::UavCommand& command);

// What the controller decided at one step (stage, failsafe, solver, reference point).
msg::ControlTrace to_trace(const mission::ControllerStatus& status, std::uint32_t uav_id,
                           double stamp_s);
// The status fields a trace carries; the others keep their defaults. Unknown enum values
// read as the safe side (failed task, solver error failsafe).
mission::ControllerStatus from_msg(const msg::ControlTrace& trace);

// What the ground station shows (10 Hz): `state` is the task's, `relative` the UAV's
// state in the reference frame.
struct UavStatusInputs {
  std::uint32_t uav_id = 0;
  double stamp_s = 0.0;
  std::string task_id;  // empty: no task
  std::uint32_t process_count = 0;
  mission::MissionState state = mission::MissionState::NotStarted;
  const mission::ControllerOutput* output = nullptr;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  bool payload_attached = false;
  std::uint64_t rejected_samples = 0;  // the intake's count (saturates on the wire)
  // The largest clock offset to a peer whose samples the agent takes (signed: the peer's
  // clock minus ours), and that peer (host/process); empty: none measured. Non-finite
  // reads as 0 on the wire.
  double max_clock_offset_ms = 0.0;
  std::string max_offset_peer;
};
msg::UavStatus to_status(const UavStatusInputs& in);

}  // namespace cover::wire

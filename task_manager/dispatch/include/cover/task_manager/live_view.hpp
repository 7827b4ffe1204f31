#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace cover::task_manager {

// The UAV agent's latest heartbeat (UavStatus) and task status, as the process saw them.
struct AgentReport {
  int uav_id = 0;
  double heard_s = 0.0;  // when its last heartbeat arrived (wall clock, Unix seconds)
  std::string task_id;   // the task the agent flies or last flew ("" none)
  enum class AgentTask : std::uint8_t {
    None,
    Pending,
    Running,
    Succeeded,
    Failed,
    Cancelled,
    Rejected
  };
  AgentTask task_state = AgentTask::None;
  std::string message;   // the agent's reason / status line
  std::string failsafe;  // the agent's failsafe (mission::to_string), "" not reported
};

// What the manager sees of the fleet right now (filled from DDS heartbeats by the process).
struct LiveView {
  std::map<int, AgentReport> agents;      // by UAV id
  std::map<int, double> ugv_imu_heard_s;  // UGV id -> when its IMU was last heard
};

}  // namespace cover::task_manager

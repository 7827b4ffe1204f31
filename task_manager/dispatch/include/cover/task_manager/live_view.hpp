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

// A UAV's autopilot as the flight-controller bridge on its companion computer reports it
// (cover/uav/<u>/fc). Only UAVs flown through a bridge have one; the simulator's direct
// path has none.
struct AutopilotReport {
  double heard_s = 0.0;  // when its last state arrived (wall clock, Unix seconds)
  // Why the autopilot does not fly COVER's setpoints now (link lost, not in its offboard
  // mode, disarmed), in words a person understands; empty: ready (armed, OFFBOARD /
  // GUIDED_NOGPS, link up).
  std::string not_ready;
};

// What the manager sees of the fleet right now (filled from DDS heartbeats by the process).
struct LiveView {
  std::map<int, AgentReport> agents;          // by UAV id
  std::map<int, double> ugv_imu_heard_s;      // UGV id -> when its IMU was last heard
  std::map<int, AutopilotReport> autopilots;  // by UAV id: those with a bridge
};

}  // namespace cover::task_manager

#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cover/vocabulary/final_action.hpp"
#include "cover/vocabulary/motion_limits.hpp"

namespace cover::mission {

// Reading a task from YAML and checking it: cover/mission/task_file.hpp.

// One transition process Gi -> Gj with its three stage transition points. The field names
// mirror the DDS type `TransitionTask`, so the YAML and the wire format stay one format.
struct TransitionProcess {
  int from_ugv = 0;  // Gi: reference frame of the initial stage
  int to_ugv = 1;    // Gj: reference frame of the transition and final stages
  Eigen::Vector3d initial_point_m{0.0, 0.0, 1.0};     // in Gi, end of the initial stage
  Eigen::Vector3d transition_point_m{0.0, 0.0, 1.0};  // in Gj, end of the transition stage
  Eigen::Vector3d final_point_m{0.0, 0.0, 0.3};       // in Gj, end of the final stage
  FinalAction final_action = FinalAction::None;
  double vmax_m_s = kDefaultVmax_m_s;    // UAV speed limit relative to the reference frame
  double amax_m_s2 = kDefaultAmax_m_s2;  // UAV acceleration limit relative to the reference frame
  // The method flying this process (a sampc::kModes name: cover, no-ref-vxy, intercept, ...);
  // empty: the UAV's configured one (sampc.yaml's mode, or its --method).
  std::string method;
};

// Task ids: 1..64 characters of A-Z a-z 0-9 _ - . : @ / + (validate_task checks it).
inline constexpr std::size_t kMaxTaskIdLength = 64;
bool is_valid_task_id(const std::string& id);

// A task: processes executed in order; the reference frame switches k0 -> k1 -> ... -> kn.
struct Task {
  std::string task_id = "task";
  int uav_id = 0;
  std::vector<TransitionProcess> processes;

  // The UGVs the task flies between, each once, in the order the processes name them.
  std::vector<int> ugvs() const;
};

// Repeats the task's processes cyclically until it has `process_count` of them (Table 1's
// cyclic G0 <-> G1 transitions are two processes repeated). Final actions are kept.
Task repeat_processes(const Task& task, int process_count);

}  // namespace cover::mission

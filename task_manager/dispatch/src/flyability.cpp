#include "cover/task_manager/flyability.hpp"
#include "cover/mission/task_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cover/config/config_error.hpp"

namespace cover::task_manager {
namespace {

// Values as a person typed them: 9, 3.5, 0.25 (not 9.000000).
std::string number(double value) {
  if (std::isnan(value)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

// Durations to a tenth of a second: "3.2 s".
std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", value);
  return text;
}

std::optional<std::string> check_point(const Eigen::Vector3d& point, const std::string& where,
                                       const TaskLimits& limits) {
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const std::string name = where + "." + kAxes[axis];
    const double value = point[axis];
    if (std::isnan(value)) return name + " is NaN";
    if (!std::isfinite(value)) return name + " is infinite";
    if (axis < 2 && std::abs(value) > limits.max_horizontal_m) {
      return name + " " + number(value) + " m is beyond the +-" + number(limits.max_horizontal_m) +
             " m limit";
    }
  }
  if (point.z() < limits.min_z_m) {
    return where + ".z " + number(point.z()) + " m is below the " + number(limits.min_z_m) +
           " m limit";
  }
  if (point.z() > limits.max_z_m) {
    return where + ".z " + number(point.z()) + " m is above the " + number(limits.max_z_m) +
           " m limit";
  }
  return std::nullopt;
}

std::optional<std::string> check_process(const mission::TransitionProcess& p,
                                         const TaskLimits& limits) {
  if (auto why = check_point(p.initial_point_m, "initial_point_m", limits)) return why;
  if (auto why = check_point(p.transition_point_m, "transition_point_m", limits)) return why;
  if (auto why = check_point(p.final_point_m, "final_point_m", limits)) return why;
  // Non-positive or NaN limits are left to Task::validate, which names them.
  if (p.vmax_m_s > limits.max_vmax_m_s) {
    return "vmax_m_s " + number(p.vmax_m_s) + " is above the vehicle's " +
           number(limits.max_vmax_m_s) + " m/s";
  }
  if (p.amax_m_s2 > limits.max_amax_m_s2) {
    return "amax_m_s2 " + number(p.amax_m_s2) + " is above the vehicle's " +
           number(limits.max_amax_m_s2) + " m/s^2";
  }
  return std::nullopt;
}

// The task's structure (chain, ids, final actions) is mission::Task::validate's; every UGV
// the task names is allowed there, whether it is up is checked against the live view.
std::optional<std::string> check_structure(const mission::Task& task) {
  const std::vector<int> ugvs = task.ugvs();
  const int ugv_count = ugvs.empty() ? 1 : *std::max_element(ugvs.begin(), ugvs.end()) + 1;
  try {
    mission::validate_task(task, std::max(ugv_count, 1));
  } catch (const config::ConfigError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

std::optional<std::string> check_uav(int uav_id, const LiveView& live, const TaskLimits& limits,
                                     double now_s) {
  const std::string uav = "UAV " + std::to_string(uav_id);
  const auto agent = live.agents.find(uav_id);
  if (agent == live.agents.end()) return uav + " is not up (never heard)";
  const double silence_s = now_s - agent->second.heard_s;
  if (silence_s > limits.heartbeat_timeout_s) {
    return uav + " is not up (no heartbeat for " + seconds(silence_s) + ")";
  }
  return std::nullopt;
}

std::optional<std::string> check_ugvs(const mission::Task& task, const LiveView& live,
                                      const TaskLimits& limits, double now_s) {
  for (const int k : task.ugvs()) {
    const std::string ugv = "UGV " + std::to_string(k) + " is not publishing its IMU";
    const auto imu = live.ugv_imu_heard_s.find(k);
    if (imu == live.ugv_imu_heard_s.end()) return ugv;
    const double silence_s = now_s - imu->second;
    if (silence_s > limits.heartbeat_timeout_s) {
      return ugv + " (not heard for " + seconds(silence_s) + ")";
    }
  }
  return std::nullopt;
}
}  // namespace

std::optional<std::string> why_not_recordable(const mission::Task& task,
                                              const std::string& submitter,
                                              const std::string& request_id) {
  if (!mission::is_valid_task_id(task.task_id)) {
    return "task_id must be 1.." + std::to_string(mission::kMaxTaskIdLength) +
           " characters of A-Z a-z 0-9 _ - . : @ / +";
  }
  const auto readable = [](const std::string& text) {
    if (text.empty() || text.size() > kMaxSubmitterLength) return false;
    return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  };
  if (!readable(submitter)) {
    return "submitter must be 1.." + std::to_string(kMaxSubmitterLength) +
           " printable ASCII characters";
  }
  if (!readable(request_id)) {
    return "request_id must be 1.." + std::to_string(kMaxSubmitterLength) +
           " printable ASCII characters";
  }
  return std::nullopt;
}

std::optional<std::string> why_not_sound(const mission::Task& task, const TaskLimits& limits) {
  for (std::size_t i = 0; i < task.processes.size(); ++i) {
    if (auto why = check_process(task.processes[i], limits)) {
      return "process " + std::to_string(i) + ": " + *why;
    }
  }
  return check_structure(task);
}

std::optional<std::string> why_not_flyable(const mission::Task& task, const LiveView& live,
                                           const TaskLimits& limits, double now_s) {
  if (auto why = why_not_sound(task, limits)) return why;
  if (auto why = check_uav(task.uav_id, live, limits, now_s)) return why;
  return check_ugvs(task, live, limits, now_s);
}

bool names_unheard(const mission::Task& task, const LiveView& live, int max_uavs, int max_ugvs) {
  return first_unheard(task, live, max_uavs, max_ugvs).has_value();
}

std::optional<std::string> first_unheard(const mission::Task& task, const LiveView& live,
                                         int max_uavs, int max_ugvs) {
  const auto unheard = [](int id, int max_id, const auto& heard) {
    return id >= 0 && id < max_id && heard.find(id) == heard.end();
  };
  if (unheard(task.uav_id, max_uavs, live.agents)) return "UAV " + std::to_string(task.uav_id);
  for (const int k : task.ugvs()) {
    if (unheard(k, max_ugvs, live.ugv_imu_heard_s)) return "UGV " + std::to_string(k);
  }
  return std::nullopt;
}

}  // namespace cover::task_manager

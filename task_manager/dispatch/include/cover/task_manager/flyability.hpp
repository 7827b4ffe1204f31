#pragma once

#include <optional>
#include <string>

#include "cover/mission/task.hpp"
#include "cover/task_manager/live_view.hpp"
#include "cover/task_manager/task_limits.hpp"

namespace cover::task_manager {

// nullopt when the task can be flown now; else one reason a person understands, e.g.
// "process 2: final_point_m.z is NaN", "process 0: vmax_m_s 9 is above the vehicle's 3 m/s",
// mission::Task::validate's message, "UAV 1 is not up (no heartbeat for 3.2 s)",
// "UGV 3 is not publishing its IMU". The task's own faults come first: they do not go away
// by waiting, while a UAV or UGV that is down may come up.
std::optional<std::string> why_not_flyable(const mission::Task& task, const LiveView& live,
                                           const TaskLimits& limits, double now_s);

}  // namespace cover::task_manager

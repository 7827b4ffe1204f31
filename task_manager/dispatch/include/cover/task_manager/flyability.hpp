#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "cover/task_manager/live_view.hpp"
#include "cover/task_manager/task_limits.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

// nullopt when the submission can be recorded at all (queued or rejected); else why not: a
// task id no task can have (mission::is_valid_task_id), a submitter or request id that is
// empty, longer than kMaxSubmitterLength or not printable ASCII. Such a submission is
// answered but not stored, and not echoed into a log: the store and the logs keep only what
// a person can read back, and a flood of junk ids cannot fill the database.
inline constexpr std::size_t kMaxSubmitterLength = 512;
std::optional<std::string> why_not_recordable(const mission::Task& task,
                                              const std::string& submitter,
                                              const std::string& request_id);

// nullopt when the task can be flown now; else one reason a person understands, e.g.
// "process 2: final_point_m.z is NaN", "process 0: vmax_m_s 9 is above the vehicle's 3 m/s",
// mission::Task::validate's message, "UAV 1 is not up (no heartbeat for 3.2 s)",
// "UGV 3 is not publishing its IMU". The task's own faults come first: they do not go away
// by waiting, while a UAV or UGV that is down may come up.
std::optional<std::string> why_not_flyable(const mission::Task& task, const LiveView& live,
                                           const TaskLimits& limits, double now_s);

// The first half of why_not_flyable: the task's own faults, whatever the fleet's state.
std::optional<std::string> why_not_sound(const mission::Task& task, const TaskLimits& limits);

// Whether the task names a vehicle that could be heard (a UAV id below max_uavs, a UGV id
// below max_ugvs: the ids the manager listens to) but has never been heard in `live`. A
// manager that has just started waits for such a vehicle before judging the task, since
// discovering a participant can take seconds; an id it does not listen to never comes up.
bool names_unheard(const mission::Task& task, const LiveView& live, int max_uavs, int max_ugvs);
// The first such vehicle, as a person names it ("UAV 0", "UGV 7"); nullopt when none.
std::optional<std::string> first_unheard(const mission::Task& task, const LiveView& live,
                                         int max_uavs, int max_ugvs);

}  // namespace cover::task_manager

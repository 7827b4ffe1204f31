#pragma once

#include <string>
#include <vector>

#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

// What a submission changes in a task known under its id, one entry per field, each as
// "processes[0].to_ugv 1 -> 7" (the known value, then the submitted one), in field order:
// uav_id, then the processes (their count, then each one's fields). Empty when the two are
// the same task. Values are compared as the store keeps them (task_to_json).
std::vector<std::string> task_differences(const mission::Task& known,
                                          const mission::Task& submitted);

}  // namespace cover::task_manager

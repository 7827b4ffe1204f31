#pragma once

#include <string>

#include "cover/vocabulary/task.hpp"

namespace cover::task_manager {

// A task as JSON, every field: ids, points as [x, y, z], final_action as
// "none" | "land" | "deliver", limits. Non-finite numbers (a rejected task may hold them)
// are written as the strings "nan", "inf", "-inf" so they survive the round trip.
std::string task_to_json(const mission::Task& task);

// Throws StoreError on malformed text or a missing / mistyped field.
mission::Task task_from_json(const std::string& text);

}  // namespace cover::task_manager

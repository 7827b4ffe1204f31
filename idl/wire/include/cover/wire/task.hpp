#pragma once

#include <cstdint>
#include <string>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::wire {

msg::TransitionTask to_msg(const mission::Task& task, double stamp_s);
// Field by field, not validated (UavLoop::give_task validates and rejects with the reason).
// An unknown final action reads as a NaN final point, which validation then rejects.
mission::Task from_msg(const msg::TransitionTask& task);

}  // namespace cover::wire

#pragma once

#include "cover/msg/types.hpp"
#include "cover/task_manager/task_record.hpp"
#include "cover/task_manager/task_state.hpp"

namespace cover::task_manager {

// The manager's record as ground stations receive it (cover/manager/reply).
msg::ManagedTask to_msg(const TaskRecord& record);
msg::ManagedTaskState to_msg(TaskState state);

}  // namespace cover::task_manager

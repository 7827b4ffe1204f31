#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "cover/msg/types.hpp"
#include "cover/vocabulary/stage_decision.hpp"

namespace cover::wire {

// Progress over the whole task in [0, 1]: finished processes plus the stage fraction.
double task_progress(const mission::StageDecision& decision, std::size_t process_count);

msg::TaskStatus to_task_status(const std::string& task_id, std::uint32_t uav_id, double stamp_s,
                               const mission::StageDecision& decision, std::size_t process_count,
                               const std::string& message);
// A task the UAV refused (TASK_REJECTED with the reason).
msg::TaskStatus rejected_task_status(const msg::TransitionTask& task, std::uint32_t uav_id,
                                     double stamp_s, const std::string& reason);

}  // namespace cover::wire

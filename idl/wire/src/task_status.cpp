#include "cover/wire/task_status.hpp"

#include <algorithm>

#include "cover/wire/eigen.hpp"
#include "cover/wire/enums.hpp"

namespace cover::wire {

double task_progress(const mission::StageDecision& decision, std::size_t process_count) {
  if (process_count == 0) return 0.0;
  if (decision.state == mission::MissionState::Complete) return 1.0;
  if (decision.state == mission::MissionState::NotStarted) return 0.0;
  const double stages_done = static_cast<double>(decision.process_index) * 3.0 +
                             static_cast<double>(static_cast<int>(decision.stage));
  return std::clamp(stages_done / (3.0 * static_cast<double>(process_count)), 0.0, 1.0);
}

msg::TaskStatus to_task_status(const std::string& task_id, std::uint32_t uav_id, double stamp_s,
                               const mission::StageDecision& decision, std::size_t process_count,
                               const std::string& message) {
  msg::TaskStatus m;
  m.task_id = task_id;
  m.uav_id = uav_id;
  m.stamp_ns = to_stamp_ns(stamp_s);
  m.state = to_msg(decision.state);
  m.process_index = static_cast<std::uint32_t>(decision.process_index);
  m.stage = to_msg(decision.stage, decision.state);
  m.progress = task_progress(decision, process_count);
  m.message = message;
  return m;
}

msg::TaskStatus rejected_task_status(const msg::TransitionTask& task, std::uint32_t uav_id,
                                     double stamp_s, const std::string& reason) {
  msg::TaskStatus m;
  m.task_id = task.task_id;
  m.uav_id = uav_id;
  m.stamp_ns = to_stamp_ns(stamp_s);
  m.state = msg::TaskState::TASK_REJECTED;
  m.stage = msg::Stage::STAGE_IDLE;
  m.message = reason;
  return m;
}

}  // namespace cover::wire

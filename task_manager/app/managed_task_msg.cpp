#include "managed_task_msg.hpp"

#include "cover/wire/eigen.hpp"

namespace cover::task_manager {

msg::ManagedTaskState to_msg(TaskState state) {
  switch (state) {
    case TaskState::Queued:
      return msg::ManagedTaskState::MANAGED_QUEUED;
    case TaskState::Dispatched:
      return msg::ManagedTaskState::MANAGED_DISPATCHED;
    case TaskState::Running:
      return msg::ManagedTaskState::MANAGED_RUNNING;
    case TaskState::Succeeded:
      return msg::ManagedTaskState::MANAGED_SUCCEEDED;
    case TaskState::Failed:
      return msg::ManagedTaskState::MANAGED_FAILED;
    case TaskState::Aborted:
      return msg::ManagedTaskState::MANAGED_ABORTED;
    case TaskState::Rejected:
      return msg::ManagedTaskState::MANAGED_REJECTED;
  }
  return msg::ManagedTaskState::MANAGED_FAILED;
}

msg::ManagedTask to_msg(const TaskRecord& r) {
  msg::ManagedTask m;
  m.task_id = r.task_id;
  m.uav_id = static_cast<std::uint32_t>(r.uav_id < 0 ? 0 : r.uav_id);
  m.submitter = r.submitter;
  m.queue_position = r.queue_position;
  m.state = to_msg(r.state);
  m.submitted_ns = wire::to_stamp_ns(r.submitted_s);
  m.updated_ns = wire::to_stamp_ns(r.updated_s);
  m.reason = r.reason;
  m.process_count = static_cast<std::uint32_t>(r.task.processes.size());
  return m;
}

}  // namespace cover::task_manager

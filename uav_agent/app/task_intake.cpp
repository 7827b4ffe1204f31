#include "task_intake.hpp"

namespace cover::uav_agent {

TaskIntake::TaskIntake(dds::Participant& participant, std::uint32_t uav_id) : uav_id_(uav_id) {
  task_reader_ =
      participant.make_reader(dds::topics::task_request(), [this](const msg::TransitionTask& t) {
        if (t.uav_id != uav_id_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        tasks_.push_back(t);
      });
  abort_reader_ =
      participant.make_reader(dds::topics::task_abort(), [this](const msg::TaskAbort& a) {
        if (a.uav_id != uav_id_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        aborts_.push_back(a);
      });
}

std::optional<msg::TransitionTask> TaskIntake::take_task() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tasks_.empty()) return std::nullopt;
  msg::TransitionTask task = std::move(tasks_.front());
  tasks_.pop_front();
  return task;
}

std::optional<msg::TaskAbort> TaskIntake::take_abort() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (aborts_.empty()) return std::nullopt;
  msg::TaskAbort abort = std::move(aborts_.front());
  aborts_.pop_front();
  return abort;
}

}  // namespace cover::uav_agent

#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::uav_agent {

// Tasks and aborts for this UAV from cover/task/request and cover/task/abort, queued by
// the receive threads and taken by the control thread between steps.
class TaskIntake {
 public:
  TaskIntake(dds::Participant& participant, std::uint32_t uav_id);

  std::optional<msg::TransitionTask> take_task();
  std::optional<msg::TaskAbort> take_abort();

 private:
  std::uint32_t uav_id_;
  std::mutex mutex_;
  std::deque<msg::TransitionTask> tasks_;
  std::deque<msg::TaskAbort> aborts_;
  dds::Reader<msg::TransitionTask> task_reader_;
  dds::Reader<msg::TaskAbort> abort_reader_;
};

}  // namespace cover::uav_agent

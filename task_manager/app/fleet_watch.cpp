#include "fleet_watch.hpp"

#include "cover/clock/clock.hpp"
#include "cover/wire/enums.hpp"

namespace cover::task_manager {
namespace {

AgentReport::AgentTask agent_task(msg::TaskState state) {
  using T = AgentReport::AgentTask;
  switch (state) {
    case msg::TaskState::TASK_PENDING:
      return T::Pending;
    case msg::TaskState::TASK_RUNNING:
      return T::Running;
    case msg::TaskState::TASK_SUCCEEDED:
      return T::Succeeded;
    case msg::TaskState::TASK_FAILED:
      return T::Failed;
    case msg::TaskState::TASK_REJECTED:
      return T::Rejected;
    case msg::TaskState::TASK_CANCELLED:
      return T::Cancelled;
  }
  return T::Failed;  // an unknown value from a foreign writer: the safe side
}

}  // namespace

FleetWatch::FleetWatch(dds::Participant& participant, int max_uavs, int max_ugvs) {
  for (int u = 0; u < max_uavs; ++u) {
    uav_readers_.push_back(
        participant.make_reader(dds::topics::uav_status(static_cast<std::uint32_t>(u)),
                                [this](const msg::UavStatus& s) { on_uav_status(s); }));
  }
  for (int k = 0; k < max_ugvs; ++k) {
    ugv_readers_.push_back(
        participant.make_reader(dds::topics::ugv_imu(static_cast<std::uint32_t>(k)),
                                [this](const msg::UgvImu& imu) { on_ugv_imu(imu); }));
  }
  task_reader_ = participant.make_reader(dds::topics::task_status(),
                                         [this](const msg::TaskStatus& s) { on_task_status(s); });
}

void FleetWatch::on_uav_status(const msg::UavStatus& s) {
  std::lock_guard<std::mutex> lock(mutex_);
  AgentReport& report = view_.agents[static_cast<int>(s.uav_id)];
  report.uav_id = static_cast<int>(s.uav_id);
  report.heard_s = clock::system_s();
  report.task_id = s.task_id;
  // An agent without a task reports PENDING with no id: idle.
  report.task_state = s.task_id.empty() ? AgentReport::AgentTask::None : agent_task(s.task_state);
  const auto message = task_messages_.find(s.task_id);
  report.message = message == task_messages_.end() ? "" : message->second;
  const auto failsafe = wire::from_msg(s.failsafe);
  report.failsafe = failsafe ? mission::to_string(*failsafe) : "unknown";
}

void FleetWatch::on_task_status(const msg::TaskStatus& s) {
  std::lock_guard<std::mutex> lock(mutex_);
  task_messages_[s.task_id] = s.message;
}

void FleetWatch::on_ugv_imu(const msg::UgvImu& imu) {
  const double now = clock::system_s();
  std::lock_guard<std::mutex> lock(mutex_);
  view_.ugv_imu_heard_s[static_cast<int>(imu.ugv_id)] = now;
}

LiveView FleetWatch::view() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return view_;
}

}  // namespace cover::task_manager

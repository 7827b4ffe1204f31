#include "fleet_intake.hpp"

#include "cover/vocabulary/task.hpp"
#include "cover/wire/enums.hpp"
#include "cover/wire/fc_state.hpp"

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

// An agent without a task reports an empty id; any other must be one a task can have.
bool known_task_id(const std::string& id) {
  return id.empty() || mission::is_valid_task_id(id);
}

}  // namespace

FleetIntake::FleetIntake(int max_uavs, int max_ugvs, wire::IntakeLimits limits)
    : max_uavs_(max_uavs), max_ugvs_(max_ugvs), limits_(limits) {
  limits_.validate();
}

std::optional<wire::Rejection> FleetIntake::counted(std::optional<wire::Rejection> why) {
  if (why) rejections_.add(*why);
  return why;
}

std::optional<wire::Rejection> FleetIntake::on_uav_status(const msg::UavStatus& s, int topic_id,
                                                          double now_s) {
  if (topic_id < 0 || topic_id >= max_uavs_ || s.uav_id != static_cast<std::uint32_t>(topic_id) ||
      !known_task_id(s.task_id)) {
    return counted(wire::Rejection::UnknownId);
  }
  AgentReport& report = view_.agents[topic_id];
  report.uav_id = topic_id;
  report.heard_s = now_s;
  report.task_id = s.task_id;
  // An agent without a task reports PENDING with no id: idle.
  report.task_state = s.task_id.empty() ? AgentReport::AgentTask::None : agent_task(s.task_state);
  const auto message = task_messages_.find(s.task_id);
  report.message = message == task_messages_.end() ? "" : message->second;
  const auto failsafe = wire::from_msg(s.failsafe);
  report.failsafe = failsafe ? mission::to_string(*failsafe) : "unknown";
  return std::nullopt;
}

std::optional<wire::Rejection> FleetIntake::on_task_status(const msg::TaskStatus& s) {
  if (s.uav_id >= static_cast<std::uint32_t>(max_uavs_) || !mission::is_valid_task_id(s.task_id)) {
    return counted(wire::Rejection::UnknownId);
  }
  const auto [entry, inserted] = task_messages_.insert_or_assign(
      s.task_id, s.message.substr(0, std::min(s.message.size(), kMaxMessageLength)));
  if (inserted) {
    message_order_.push_back(s.task_id);
    if (message_order_.size() > kRememberedMessages) {
      task_messages_.erase(message_order_.front());
      message_order_.pop_front();
    }
  }
  return std::nullopt;
}

std::optional<wire::Rejection> FleetIntake::on_fc_state(const msg::FcState& state, int topic_id,
                                                        double now_s) {
  if (topic_id < 0 || topic_id >= max_uavs_ ||
      state.uav_id != static_cast<std::uint32_t>(topic_id)) {
    return counted(wire::Rejection::UnknownId);
  }
  AutopilotReport& report = view_.autopilots[topic_id];
  report.heard_s = now_s;
  // The reason ends up in the store and the logs: cut like an agent's message (mode_name
  // comes from the autopilot, through a bridge).
  const std::string why = wire::fc_not_ready_reason(state).value_or("");
  report.not_ready = why.substr(0, std::min(why.size(), kMaxMessageLength));
  return std::nullopt;
}

std::optional<wire::Rejection> FleetIntake::on_ugv_imu(const msg::UgvImu& imu, int topic_id,
                                                       double now_s) {
  if (topic_id < 0 || topic_id >= max_ugvs_) return counted(wire::Rejection::UnknownId);
  if (const auto why = wire::check_content(imu, static_cast<std::uint32_t>(topic_id), limits_)) {
    return counted(why);
  }
  view_.ugv_imu_heard_s[topic_id] = now_s;
  return std::nullopt;
}

}  // namespace cover::task_manager

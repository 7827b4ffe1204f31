#include "cover/dds/topics.hpp"

#include <cctype>

namespace cover::dds {

const std::vector<TopicInfo>& topic_catalog() {
  static const std::vector<TopicInfo> catalog = {
      {"cover/ugv/<k>/imu", "cover::idl::UgvImu", "sensor", "200 Hz",
       "UGV k's filtered IMU in G_k (ugv_agent)"},
      {"cover/uav/<u>/rel/<k>", "cover::idl::RelativeState", "sensor", "100 Hz",
       "UAV u's state relative to UGV k, in G_k (relative localisation / sim)"},
      {"cover/uav/<u>/cmd", "cover::idl::UavCommand", "command", "100 Hz",
       "thrust and body-rate command to UAV u (uav_agent)"},
      {"cover/uav/<u>/status", "cover::idl::UavStatus", "state", "10 Hz",
       "stage, reference frame, solver and failsafe state of UAV u (uav_agent)"},
      {"cover/uav/<u>/trace", "cover::idl::ControlTrace", "command", "100 Hz",
       "per control step: stage, failsafe, solver, reference point of UAV u (uav_agent)"},
      {"cover/ugv/<k>/status", "cover::idl::UgvStatus", "state", "1 Hz",
       "UGV k's agent heartbeat: IMU source, rate, health (ugv_agent)"},
      {"cover/sim/clock", "cover::idl::SimClock", "command", "100 Hz",
       "the simulator's time, one sample per control period (sim)"},
      {"cover/uav/<u>/reference", "cover::idl::ReferenceTrajectory", "state", "per stage",
       "sampled reference of the current stage, for display (uav_agent)"},
      {"cover/task/request", "cover::idl::TransitionTask", "state", "on demand",
       "task sequences dispatched to a UAV (task_manager)"},
      {"cover/task/status", "cover::idl::TaskStatus", "state", "on change",
       "progress and outcome of each task (uav_agent)"},
  };
  return catalog;
}

namespace {
// Matches `name` against `pattern`, where "<x>" stands for one or more digits.
bool matches(std::string_view pattern, std::string_view name) {
  std::size_t p = 0, n = 0;
  while (p < pattern.size()) {
    if (pattern[p] == '<') {
      const std::size_t close = pattern.find('>', p);
      const std::size_t start = n;
      while (n < name.size() && std::isdigit(static_cast<unsigned char>(name[n]))) ++n;
      if (n == start) return false;
      p = close + 1;
    } else {
      if (n >= name.size() || name[n] != pattern[p]) return false;
      ++p;
      ++n;
    }
  }
  return n == name.size();
}
}  // namespace

const TopicInfo* find_topic(std::string_view topic_name) {
  for (const auto& info : topic_catalog()) {
    if (matches(info.pattern, topic_name)) return &info;
  }
  return nullptr;
}

std::string ugv_imu_topic(std::uint32_t ugv_id) {
  return "cover/ugv/" + std::to_string(ugv_id) + "/imu";
}
std::string relative_state_topic(std::uint32_t uav_id, std::uint32_t ugv_id) {
  return "cover/uav/" + std::to_string(uav_id) + "/rel/" + std::to_string(ugv_id);
}
std::string uav_command_topic(std::uint32_t uav_id) {
  return "cover/uav/" + std::to_string(uav_id) + "/cmd";
}
std::string uav_status_topic(std::uint32_t uav_id) {
  return "cover/uav/" + std::to_string(uav_id) + "/status";
}
std::string uav_reference_topic(std::uint32_t uav_id) {
  return "cover/uav/" + std::to_string(uav_id) + "/reference";
}

}  // namespace cover::dds

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cover/dds/qos.hpp"

namespace cover::dds {

// One entry of the topic catalogue (docs/topics.md lists the same, and a test checks it).
// `pattern` uses <k> for a UGV id and <u> for a UAV id.
struct TopicInfo {
  std::string pattern;
  std::string type_name;  // scoped IDL name, e.g. "cover::idl::UgvImu"
  std::string qos_profile;
  std::string rate;
  std::string description;
};

const std::vector<TopicInfo>& topic_catalog();

// The catalogue entry a concrete topic name belongs to, or nullptr (placeholders match
// decimal ids).
const TopicInfo* find_topic(std::string_view topic_name);

std::string ugv_imu_topic(std::uint32_t ugv_id);
std::string relative_state_topic(std::uint32_t uav_id, std::uint32_t ugv_id);
std::string uav_command_topic(std::uint32_t uav_id);
std::string uav_status_topic(std::uint32_t uav_id);
std::string uav_reference_topic(std::uint32_t uav_id);
inline constexpr const char* kTaskRequestTopic = "cover/task/request";
inline constexpr const char* kTaskStatusTopic = "cover/task/status";

}  // namespace cover::dds

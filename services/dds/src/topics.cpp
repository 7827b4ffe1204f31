#include "cover/dds/topics.hpp"

#include <cctype>

#include "cover/dds/dds_error.hpp"

namespace cover::dds {
namespace {

template <typename T, typename... Ids>
TopicInfo info_of(const TopicDescriptor<T, Ids...>& row) {
  return {std::string(row.pattern), T::kTypeName,          row.qos().name,
          std::string(row.rate),    std::string(row.flow), std::string(row.description)};
}

constexpr std::size_t kMaxProcessName = 64;

bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}
bool topic_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}
bool process_name_char(char c) {
  return topic_char(c) || c == '-' || c == '.';
}

// Matches `name` against `pattern`, where <process> stands for a process's topic name part
// (ProcessName) and any other "<x>" for one or more digits.
bool matches(std::string_view pattern, std::string_view name) {
  std::size_t p = 0, n = 0;
  while (p < pattern.size()) {
    if (pattern[p] == '<') {
      const std::size_t close = pattern.find('>', p);
      const bool process = pattern.substr(p, close + 1 - p) == ProcessName::kPlaceholder;
      const std::size_t start = n;
      while (n < name.size() && (process ? topic_char(name[n]) : is_digit(name[n]))) ++n;
      if (n == start || (process && n - start > kMaxProcessName)) return false;
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

std::string substitute(std::string_view pattern, std::string_view placeholder,
                       std::uint32_t value) {
  std::string name(pattern);
  const std::size_t at = name.find(placeholder);
  if (at != std::string::npos) name.replace(at, placeholder.size(), std::to_string(value));
  return name;
}

std::string substitute(std::string_view pattern, std::string_view placeholder,
                       const std::string& value) {
  std::string name(pattern);
  const std::size_t at = name.find(placeholder);
  if (at != std::string::npos) name.replace(at, placeholder.size(), value);
  return name;
}

ProcessName ProcessName::of(std::string_view process) {
  std::string part(process);
  for (char& c : part) {
    if (!topic_char(c)) c = '_';
  }
  return ProcessName{std::move(part)};
}

bool valid_process_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxProcessName) return false;
  for (const char c : name) {
    if (!process_name_char(c)) return false;
  }
  return true;
}

namespace topics {

Topic<msg::TimeSyncReply> time_reply(const std::string& asker) {
  if (!valid_process_name(asker)) {
    throw DdsError("'" + asker +
                   "' cannot name a clock reply topic: 1 to 64 letters, digits, '-', '_' or '.'");
  }
  return bind<msg::TimeSyncReply>(ProcessName::of(asker));
}

std::vector<std::string> clock_askers(std::uint32_t uavs, std::uint32_t ugvs) {
  std::vector<std::string> askers{"cover-task-manager"};
  for (std::uint32_t u = 0; u < uavs; ++u) askers.push_back("cover-uav-agent-" + std::to_string(u));
  for (std::uint32_t k = 0; k < ugvs; ++k) askers.push_back("cover-ugv-agent-" + std::to_string(k));
  return askers;
}

}  // namespace topics

const std::vector<TopicInfo>& topic_catalog() {
  static const std::vector<TopicInfo> catalog =
      std::apply([](const auto&... rows) { return std::vector<TopicInfo>{info_of(rows)...}; },
                 topics::kCatalog);
  return catalog;
}

const TopicInfo* find_topic(std::string_view topic_name) {
  for (const auto& info : topic_catalog()) {
    if (matches(info.pattern, topic_name)) return &info;
  }
  return nullptr;
}

const TopicInfo& require_catalogued(std::string_view name, std::string_view type_name) {
  const TopicInfo* info = find_topic(name);
  if (!info) {
    throw DdsError("topic '" + std::string(name) +
                   "' is not in the catalogue (see `cover topics`)");
  }
  if (info->type_name != type_name) {
    throw DdsError("topic '" + std::string(name) + "' carries " + info->type_name + ", not " +
                   std::string(type_name));
  }
  return *info;
}

void require_uncatalogued(std::string_view name) {
  if (const TopicInfo* info = find_topic(name)) {
    throw DdsError("topic '" + std::string(name) + "' is catalogued as " + info->pattern + " (" +
                   info->type_name + ", QoS " + info->qos_profile +
                   "): use its cover::dds::topics accessor, not Topic::uncatalogued");
  }
}

}  // namespace cover::dds

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

std::string substitute(std::string_view pattern, std::string_view placeholder,
                       std::uint32_t value) {
  std::string name(pattern);
  const std::size_t at = name.find(placeholder);
  if (at != std::string::npos) name.replace(at, placeholder.size(), std::to_string(value));
  return name;
}

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

#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "cover/dds/qos.hpp"
#include "cover/dds/topic.hpp"

namespace cover::dds {

// The ids a topic pattern is parameterised by, each with its placeholder. Distinct types
// so that a descriptor states which ids its pattern takes, in which order.
struct UgvId {
  static constexpr std::string_view kPlaceholder = "<k>";
  std::uint32_t value;
};
struct UavId {
  static constexpr std::string_view kPlaceholder = "<u>";
  std::uint32_t value;
};
// A process's own topic, which only it reads (the replies to its clock requests): its
// name ("cover-uav-agent-0", a valid_process_name) as a topic name part, each '-' and '.'
// an '_' ("cover_uav_agent_0"): Cyclone DDS takes only [A-Za-z0-9_/] in a topic name.
struct ProcessName {
  static constexpr std::string_view kPlaceholder = "<process>";
  std::string value;
  static ProcessName of(std::string_view process);
};

// Whether `name` may name a process in the clock exchange and its topic: 1 to 64 letters,
// digits, '-', '_' or '.'.
bool valid_process_name(std::string_view name);

// `pattern` with its first `placeholder` replaced by the decimal `value`.
std::string substitute(std::string_view pattern, std::string_view placeholder, std::uint32_t value);
// `pattern` with its first `placeholder` replaced by `value`.
std::string substitute(std::string_view pattern, std::string_view placeholder,
                       const std::string& value);

// One catalogue entry: everything about a topic, in one place. `bind` makes the concrete
// Topic<T> for given ids; topic_catalog() and docs/topics.md are the runtime view of it.
template <typename T, typename... Ids>
struct TopicDescriptor {
  using Message = T;

  std::string_view pattern;  // <k>: UGV id, <u>: UAV id, <process>: a process name
  QosProfile (*qos)();       // one of the named profiles (qos.hpp)
  std::string_view rate;
  std::string_view flow;  // "publisher -> subscribers"
  std::string_view description;

  Topic<T> bind(Ids... ids) const {
    std::string name(pattern);
    ((name = substitute(name, Ids::kPlaceholder, ids.value)), ...);
    return Topic<T>(std::move(name), qos(), true);
  }
};

}  // namespace cover::dds

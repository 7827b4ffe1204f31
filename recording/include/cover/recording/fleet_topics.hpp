#pragma once

#include <cstdint>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "cover/dds/topics.hpp"
#include "cover/vocabulary/fleet_size.hpp"

namespace cover::recording {

// The vehicles whose topics a recorder, player or `cover fleet` binds: UAV ids 0..uavs-1,
// UGV ids 0..ugvs-1.
struct FleetSize {
  std::uint32_t uavs = fleet::kDefaultUavs;
  std::uint32_t ugvs = fleet::kDefaultUgvs;
};

// True when `topic` matches one of the shell globs (fnmatch; `*` spans '/'), or `globs`
// is empty.
bool topic_selected(const std::string& topic, const std::vector<std::string>& globs);

namespace detail {

template <typename Id>
std::uint32_t id_count(const FleetSize& fleet) {
  if constexpr (std::is_same_v<Id, dds::UavId>) {
    return fleet.uavs;
  } else {
    return fleet.ugvs;
  }
}

template <typename T, typename... Ids, typename F, typename... Bound>
void bind_each(const dds::TopicDescriptor<T, Ids...>& row, const FleetSize& fleet, F& f,
               Bound... bound) {
  if constexpr (sizeof...(Bound) == sizeof...(Ids)) {
    f(row.bind(bound...));
  } else {
    using Next = std::tuple_element_t<sizeof...(Bound), std::tuple<Ids...>>;
    if constexpr (std::is_same_v<Next, dds::ProcessName>) {
      // A topic per asking process: the fleet's askers'.
      for (const std::string& asker : dds::topics::clock_askers(fleet.uavs, fleet.ugvs)) {
        bind_each(row, fleet, f, bound..., Next::of(asker));
      }
    } else {
      for (std::uint32_t id = 0; id < id_count<Next>(fleet); ++id) {
        bind_each(row, fleet, f, bound..., Next{id});
      }
    }
  }
}

}  // namespace detail

// Calls f(dds::Topic<T>) for every concrete topic of the catalogue in a fleet of `fleet`'s
// size (cover/uav/<u>/rel/<k> for every u and k, cover/time/reply/<process> for every
// process that asks clocks...), in catalogue order.
template <typename F>
void for_each_fleet_topic(const FleetSize& fleet, F&& f) {
  std::apply([&](const auto&... rows) { (detail::bind_each(rows, fleet, f), ...); },
             dds::topics::kCatalog);
}

// Calls f(dds::Topic<T>) for every concrete topic of message type T's row in a fleet of
// `fleet`'s size (cover/uav/<u>/status for every u), in id order.
template <typename T, typename F>
void for_each_fleet_topic_of(const FleetSize& fleet, F&& f) {
  const auto visit = [&](const auto& row) {
    if constexpr (std::is_same_v<typename std::decay_t<decltype(row)>::Message, T>) {
      detail::bind_each(row, fleet, f);
    }
  };
  std::apply([&](const auto&... rows) { (visit(rows), ...); }, dds::topics::kCatalog);
}

}  // namespace cover::recording

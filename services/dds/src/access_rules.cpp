#include "cover/dds/access_rules.hpp"

#include <array>
#include <cstdlib>
#include <initializer_list>
#include <tuple>

#include "cover/dds/topics.hpp"

namespace cover::dds {
namespace {

// A role's right on a topic. `own_id_only`: only the process whose id is the topic's id
// of its kind (UGV agent k on cover/ugv/k/..., UAV agent u on cover/uav/u/...).
struct Grant {
  Role role = Role::Sim;
  bool own_id_only = false;
};
constexpr bool kOwn = true;

struct Grants {
  static constexpr std::size_t kMax = 8;
  std::array<Grant, kMax> items{};
  std::size_t size = 0;
  constexpr Grants(std::initializer_list<Grant> list) {
    for (const Grant& grant : list) items[size++] = grant;
  }
};

template <typename T>
struct AccessRule {
  Grants publish;
  Grants subscribe;
};

// One rule per catalogue message type. std::get<AccessRule<T>> below does not compile for
// a catalogued type without its rule here. Ground stations may watch every topic.
inline constexpr Grant kStation{Role::GroundStation};
inline constexpr std::tuple kAccess{
    AccessRule<msg::UgvImu>{{{Role::UgvAgent, kOwn}},
                            {{Role::UavAgent}, {Role::TaskManager}, kStation}},
    // The simulator's own relative states, or the motion-capture relay's (cover-sim --mocap).
    AccessRule<msg::RelativeState>{{{Role::Sim}, {Role::MocapRelay}},
                                   {{Role::UavAgent, kOwn}, kStation}},
    AccessRule<msg::UavCommand>{{{Role::UavAgent, kOwn}},
                                {{Role::Sim}, {Role::FcBridge, kOwn}, kStation}},
    AccessRule<msg::UavStatus>{{{Role::UavAgent, kOwn}},
                               {{Role::TaskManager}, {Role::Sim}, kStation}},
    AccessRule<msg::ControlTrace>{{{Role::UavAgent, kOwn}}, {{Role::Sim}, kStation}},
    AccessRule<msg::UgvStatus>{{{Role::UgvAgent, kOwn}}, {{Role::TaskManager}, kStation}},
    AccessRule<msg::SimClock>{{{Role::Sim}},
                              {{Role::UavAgent}, {Role::UgvAgent}, {Role::FcBridge}, kStation}},
    AccessRule<msg::ReferenceTrajectory>{{{Role::UavAgent, kOwn}}, {{Role::Sim}, kStation}},
    AccessRule<msg::TransitionTask>{{{Role::TaskManager}}, {{Role::UavAgent}, kStation}},
    AccessRule<msg::TaskAbort>{{{Role::TaskManager}, kStation}, {{Role::UavAgent}}},
    AccessRule<msg::ManagerRequest>{{kStation}, {{Role::TaskManager}}},
    AccessRule<msg::ManagerReply>{{{Role::TaskManager}}, {kStation}},
    AccessRule<msg::TaskStatus>{{{Role::UavAgent}}, {{Role::TaskManager}, {Role::Sim}, kStation}},
    AccessRule<msg::FcState>{{{Role::FcBridge, kOwn}},
                             {{Role::UavAgent, kOwn}, {Role::TaskManager}, kStation}},
    // Operators only: nothing but a ground station may arm, switch or land an autopilot.
    AccessRule<msg::FcRequest>{{kStation}, {{Role::FcBridge}}},
    AccessRule<msg::FcReply>{{{Role::FcBridge}}, {kStation}},
    // Clock offsets (docs/time.md): whoever takes another host's samples asks; whoever
    // stamps samples another host takes answers.
    AccessRule<msg::TimeSyncRequest>{{{Role::UavAgent}, {Role::UgvAgent}, {Role::TaskManager}},
                                     {{Role::Sim},
                                      {Role::UgvAgent},
                                      {Role::UavAgent},
                                      {Role::FcBridge},
                                      {Role::MocapRelay},
                                      kStation}},
    // A reply topic per asker (cover/time/reply/<process>): an answerer may publish on any
    // (a '*' pattern), an asker reads only its own.
    AccessRule<msg::TimeSyncReply>{
        {{Role::Sim}, {Role::UgvAgent}, {Role::UavAgent}, {Role::FcBridge}, {Role::MocapRelay}},
        {{Role::UavAgent, kOwn}, {Role::UgvAgent, kOwn}, {Role::TaskManager, kOwn}, kStation}},
};

struct RoleName {
  Role role;
  std::string_view prefix;
  bool numbered;
};
constexpr std::array<RoleName, 7> kRoleNames{{{Role::Sim, "sim", false},
                                              {Role::TaskManager, "task-manager", false},
                                              {Role::UgvAgent, "ugv-agent-", true},
                                              {Role::UavAgent, "uav-agent-", true},
                                              {Role::FcBridge, "fc-bridge-", true},
                                              {Role::GroundStation, "ground-station-", true},
                                              {Role::MocapRelay, "mocap-relay", false}}};

// The ids a concrete topic name was bound to. A <process> topic is bound either to one
// process's name (granted to that process only) or to every process ('*', granted to the
// roles with a grant on every id).
struct Binding {
  std::optional<std::uint32_t> ugv;
  std::optional<std::uint32_t> uav;
  std::optional<std::string> process;
  bool any_process = false;
};
void set(Binding& binding, UgvId id) {
  binding.ugv = id.value;
}
void set(Binding& binding, UavId id) {
  binding.uav = id.value;
}

std::uint32_t count_of(UgvId, const Fleet& fleet) {
  return fleet.ugvs;
}
std::uint32_t count_of(UavId, const Fleet& fleet) {
  return fleet.uavs;
}

// The name a process of `identity` runs as ("uav-agent-0": "cover-uav-agent-0").
std::string process_name(const Identity& identity) {
  return "cover-" + identity_name(identity);
}

bool granted(const Grants& grants, const Identity& who, const Binding& binding) {
  for (std::size_t i = 0; i < grants.size; ++i) {
    const Grant& grant = grants.items[i];
    if (grant.role != who.role) continue;
    if (binding.any_process) {
      if (!grant.own_id_only) return true;
      continue;
    }
    if (binding.process) {
      if (grant.own_id_only && *binding.process == process_name(who)) return true;
      continue;
    }
    if (!grant.own_id_only) return true;
    const std::optional<std::uint32_t> own =
        who.role == Role::UgvAgent                                 ? binding.ugv
        : who.role == Role::UavAgent || who.role == Role::FcBridge ? binding.uav
                                                                   : std::nullopt;
    if (own && *own == who.id) return true;
  }
  return false;
}

// Calls visit(name, binding) for every id combination of `row` in `fleet`.
template <typename T, typename Visit>
void for_each_binding(const TopicDescriptor<T>& row, const Fleet&, Visit visit) {
  visit(row.bind().name(), Binding{});
}
template <typename T, typename A, typename Visit>
void for_each_binding(const TopicDescriptor<T, A>& row, const Fleet& fleet, Visit visit) {
  for (std::uint32_t a = 0; a < count_of(A{}, fleet); ++a) {
    Binding binding;
    set(binding, A{a});
    visit(row.bind(A{a}).name(), binding);
  }
}
template <typename T, typename Visit>
void for_each_binding(const TopicDescriptor<T, ProcessName>& row, const Fleet& fleet, Visit visit) {
  Binding any;
  any.any_process = true;
  visit(row.bind(ProcessName{"*"}).name(), any);
  for (const Identity& identity : fleet_identities(fleet)) {
    Binding own;
    own.process = process_name(identity);
    visit(row.bind(ProcessName::of(*own.process)).name(), own);
  }
}
template <typename T, typename A, typename B, typename Visit>
void for_each_binding(const TopicDescriptor<T, A, B>& row, const Fleet& fleet, Visit visit) {
  for (std::uint32_t a = 0; a < count_of(A{}, fleet); ++a) {
    for (std::uint32_t b = 0; b < count_of(B{}, fleet); ++b) {
      Binding binding;
      set(binding, A{a});
      set(binding, B{b});
      visit(row.bind(A{a}, B{b}).name(), binding);
    }
  }
}

}  // namespace

std::string identity_name(const Identity& identity) {
  for (const auto& entry : kRoleNames) {
    if (entry.role != identity.role) continue;
    return std::string(entry.prefix) + (entry.numbered ? std::to_string(identity.id) : "");
  }
  return "";
}

std::optional<Identity> parse_identity(std::string_view name) {
  for (const auto& entry : kRoleNames) {
    if (!entry.numbered) {
      if (name == entry.prefix) return Identity{entry.role, 0};
      continue;
    }
    if (name.substr(0, entry.prefix.size()) != entry.prefix) continue;
    const std::string digits(name.substr(entry.prefix.size()));
    if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string::npos ||
        (digits.size() > 1 && digits[0] == '0')) {
      return std::nullopt;
    }
    return Identity{entry.role,
                    static_cast<std::uint32_t>(std::strtoul(digits.c_str(), nullptr, 10))};
  }
  return std::nullopt;
}

std::vector<Identity> fleet_identities(const Fleet& fleet) {
  std::vector<Identity> all{{Role::Sim, 0}, {Role::TaskManager, 0}, {Role::MocapRelay, 0}};
  for (std::uint32_t k = 0; k < fleet.ugvs; ++k) all.push_back({Role::UgvAgent, k});
  for (std::uint32_t u = 0; u < fleet.uavs; ++u) all.push_back({Role::UavAgent, u});
  for (std::uint32_t u = 0; u < fleet.uavs; ++u) all.push_back({Role::FcBridge, u});
  for (std::uint32_t n = 0; n < fleet.ground_stations; ++n) all.push_back({Role::GroundStation, n});
  return all;
}

TopicAccess topic_access(const Identity& identity, const Fleet& fleet) {
  TopicAccess access;
  std::apply(
      [&](const auto&... rows) {
        const auto add = [&](const auto& row) {
          using Message = typename std::decay_t<decltype(row)>::Message;
          const auto& rule = std::get<AccessRule<Message>>(kAccess);
          for_each_binding(row, fleet, [&](const std::string& name, const Binding& binding) {
            if (granted(rule.publish, identity, binding)) access.publish.push_back(name);
            if (granted(rule.subscribe, identity, binding)) access.subscribe.push_back(name);
          });
        };
        (add(rows), ...);
      },
      topics::kCatalog);
  return access;
}

}  // namespace cover::dds

#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cover::dds {

// Who may publish and subscribe what under DDS-Security: the roles of COVER's processes,
// their identity names, and the per-topic grants the signed permissions are made from.
// The topic names come from the catalogue (topics.hpp); a catalogued message type with
// no access rule does not compile (access_rules.cpp).

enum class Role { Sim, UgvAgent, UavAgent, FcBridge, TaskManager, GroundStation, MocapRelay };

// One process of the fleet. `id`: UGV k, UAV u or ground station n; 0 for the simulator
// and the task manager, which are one of a kind.
struct Identity {
  Role role = Role::Sim;
  std::uint32_t id = 0;
  bool operator==(const Identity& other) const { return role == other.role && id == other.id; }
};

// "sim", "task-manager", "ugv-agent-<k>", "uav-agent-<u>", "fc-bridge-<u>",
// "ground-station-<n>", "mocap-relay" (one per fleet, like the simulator).
std::string identity_name(const Identity& identity);
// The inverse of identity_name; nullopt for any other text.
std::optional<Identity> parse_identity(std::string_view name);

// How many processes of each numbered role a fleet directory has identities for.
struct Fleet {
  std::uint32_t ugvs = 2;
  std::uint32_t uavs = 1;
  std::uint32_t ground_stations = 1;
};

// Every identity of `fleet`: sim, task-manager, ugv-agent-*, uav-agent-*, ground-station-*.
std::vector<Identity> fleet_identities(const Fleet& fleet);

// The concrete topic names `identity` may publish and subscribe in `fleet`, in catalogue
// order (least privilege: e.g. only uav-agent-u publishes cover/uav/u/cmd).
struct TopicAccess {
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
};
TopicAccess topic_access(const Identity& identity, const Fleet& fleet);

}  // namespace cover::dds

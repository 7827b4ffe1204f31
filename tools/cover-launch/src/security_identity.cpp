#include "cover/launch/security_identity.hpp"

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "cover/dds/access_rules.hpp"

namespace cover::launch {
namespace {

// The value of `--id N` or `--id=N`, if any.
std::optional<std::uint32_t> id_argument(const std::vector<std::string>& args) {
  const std::string flag = "--id";
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == flag && i + 1 < args.size()) value = args[i + 1];
    if (args[i].rfind(flag + "=", 0) == 0) value = args[i].substr(flag.size() + 1);
    if (!value.empty() && value.find_first_not_of("0123456789") == std::string::npos &&
        value.size() < 7) {
      return static_cast<std::uint32_t>(std::stoul(value));
    }
  }
  return std::nullopt;
}

std::optional<dds::Identity> identity_by_role(const std::string& executable,
                                              const std::vector<std::string>& args) {
  const std::string program = std::filesystem::path(executable).filename().string();
  if (program == "cover-sim") return dds::Identity{dds::Role::Sim, 0};
  if (program == "cover-task-manager") return dds::Identity{dds::Role::TaskManager, 0};
  if (program == "cover" || program == "cover-ground-station") {
    return dds::Identity{dds::Role::GroundStation, 0};
  }
  if (program == "cover-mocap-relay") return dds::Identity{dds::Role::MocapRelay, 0};
  const auto id = id_argument(args);
  if (!id) return std::nullopt;
  if (program == "cover-ugv-agent") return dds::Identity{dds::Role::UgvAgent, *id};
  if (program == "cover-uav-agent") return dds::Identity{dds::Role::UavAgent, *id};
  if (program == "cover-fc-bridge") return dds::Identity{dds::Role::FcBridge, *id};
  return std::nullopt;
}

}  // namespace

std::string launch_identity(const std::string& process_name, const std::string& executable,
                            const std::vector<std::string>& args,
                            const std::string& explicit_identity) {
  if (!explicit_identity.empty()) {
    if (!dds::parse_identity(explicit_identity)) {
      throw std::invalid_argument("process '" + process_name + "': identity '" + explicit_identity +
                                  "' is not an identity name (sim, task-manager, ugv-agent-K, "
                                  "uav-agent-U, fc-bridge-U, ground-station-N, mocap-relay)");
    }
    return explicit_identity;
  }
  if (const auto identity = identity_by_role(executable, args)) {
    return dds::identity_name(*identity);
  }
  throw std::invalid_argument("process '" + process_name +
                              "': security is on but its DDS identity cannot be told from its "
                              "executable and --id; give it an `identity:` key");
}

}  // namespace cover::launch

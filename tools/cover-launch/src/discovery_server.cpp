#include "cover/launch/discovery_server.hpp"

#include <stdexcept>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/participant_options.hpp"

namespace cover::launch {

std::string discovery_server_for(const std::string& profile, int domain_id) {
  if (profile.empty()) return "";
  const auto options =
      dds::ParticipantOptions::load_file(config::default_config_dir() + "/dds.yaml", profile);
  if (options.discovery_server.empty()) return "";
  const dds::ServerAddress server = dds::parse_server_address(options.discovery_server);
  return server.address + ":" + std::to_string(server.port + domain_id);
}

void add_discovery_server(LaunchFile& file, const std::string& server) {
  for (const auto& process : file.processes) {
    if (process.name == kDiscoveryServerName) {
      throw std::invalid_argument(std::string("the launch file already has a process named '") +
                                  kDiscoveryServerName + "'");
    }
  }
  const dds::ServerAddress address = dds::parse_server_address(server);
  ProcessSpec spec;
  spec.name = kDiscoveryServerName;
  // The server itself, not the `fastdds discovery` Python wrapper, which does not pass a
  // SIGTERM on to it: the launcher's stop must reach the process that serves.
  spec.executable = "fast-discovery-server";
  spec.args = {"-i", std::to_string(dds::kDiscoveryServerId),
               "-l", address.address,
               "-p", std::to_string(address.port)};
  spec.respawn.enabled = false;
  for (auto& process : file.processes) process.env["COVER_DDS_DISCOVERY_SERVER"] = server;
  file.processes.insert(file.processes.begin(), spec);
}

}  // namespace cover::launch

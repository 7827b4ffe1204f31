#pragma once

#include <string>

#include "cover/launch/launch_file.hpp"

namespace cover::launch {

// The process a launch adds when its DDS profile names a Fast DDS Discovery Server.
inline constexpr const char* kDiscoveryServerName = "discovery-server";

// The server's "IPv4:port" for `profile` of config/dds.yaml on `domain_id`: the profile's
// discovery_server with the domain id added to its port, so that runs on different domains
// of one host never share a server; empty when the profile names none (or is empty).
// Throws config::ConfigError for an unknown profile.
std::string discovery_server_for(const std::string& profile, int domain_id);

// Starts `fast-discovery-server` (what `fastdds discovery` runs; Debian's fastdds-tools) first, on
// `server` ("IPv4:port"), and tells every process where it is ($COVER_DDS_DISCOVERY_SERVER). Throws
// std::invalid_argument if the file already has a process of that name.
void add_discovery_server(LaunchFile& file, const std::string& server);

}  // namespace cover::launch

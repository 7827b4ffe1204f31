#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cover::time_sync {

// "host/process": how a process names itself in the clock exchange (this host's name,
// e.g. "uav0-nx/cover-uav-agent-0").
std::string peer_name(const std::string& process);

// Whether `peer` ("host/process") is one of `patterns`, matched against its process part:
// "cover-sim" exactly, "cover-ugv-agent-*" as a prefix. Empty `patterns`: every peer.
bool peer_matches(std::string_view peer, const std::vector<std::string>& patterns);

}  // namespace cover::time_sync

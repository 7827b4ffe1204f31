#pragma once

#include <string>
#include <vector>

namespace cover::launch {

// The DDS-Security identity a process of a secure launch runs as: `explicit_identity`
// when given (the process's `identity:` key), else by role from its executable and
// (expanded) arguments: cover-sim -> sim, cover-task-manager -> task-manager,
// cover-ugv-agent --id K -> ugv-agent-K, cover-uav-agent --id U -> uav-agent-U,
// cover -> ground-station-0. Throws std::invalid_argument naming the process when neither
// gives one.
std::string launch_identity(const std::string& process_name, const std::string& executable,
                            const std::vector<std::string>& args,
                            const std::string& explicit_identity);

}  // namespace cover::launch

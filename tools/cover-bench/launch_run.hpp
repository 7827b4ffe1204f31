#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cover::bench {

// One mission through cover-launch (`--json`): the launch file under config/launch/, the
// extra flags, one DDS domain. Returns the launcher's JSON report, or an empty object when
// it gave none. The launcher's log and run directory are removed after a successful run
// and kept (their path on stderr, prefixed with `who`) otherwise, to show why.
nlohmann::json run_launch(const std::string& launch_name, const std::vector<std::string>& flags,
                          int domain, const std::string& who,
                          std::chrono::minutes timeout = std::chrono::minutes(5));

}  // namespace cover::bench

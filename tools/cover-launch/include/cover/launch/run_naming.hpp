#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>

namespace cover::launch {

// `text` with every character outside [A-Za-z0-9_] replaced by '_': the run id names
// shared-memory segments and DDS entities, where other characters are not portable.
std::string sanitize_run_id(const std::string& text);

// "<name>_<pid>", sanitised: unique among the runs alive on this host.
std::string make_run_id(const std::string& launch_name, pid_t launcher_pid);

// "runs/<name>_<YYYYmmdd-HHMMSS>" (local time) under `base_dir`; when that folder exists
// already (two runs in one second) a suffix "_2", "_3"... keeps runs apart.
std::string default_run_dir(const std::string& base_dir, const std::string& launch_name,
                            std::chrono::system_clock::time_point now);

}  // namespace cover::launch

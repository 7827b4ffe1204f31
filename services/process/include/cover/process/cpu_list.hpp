#pragma once

#include <sched.h>

#include <string>
#include <vector>

namespace cover::process {

// The CPUs in `set`, ascending.
std::vector<int> cpus_of(const cpu_set_t& set);

// "1", "0,2-3": CPUs as taskset and /proc/<pid>/status (Cpus_allowed_list) write them, runs
// of consecutive CPUs as ranges; "none" for no CPU. Any order, repeats ignored.
std::string cpu_list(std::vector<int> cpus);

}  // namespace cover::process

#pragma once

#include <string>
#include <vector>

namespace cover::launch {

// Removes every entry of `shm_dir` whose name contains `run_id` (not as part of a longer
// word: "x_12" does not name "x_123") and returns their names:
// segments a process of the run left behind (a crash, a SIGKILL). A run id shorter than
// 3 characters removes nothing, so an accident cannot empty /dev/shm.
std::vector<std::string> remove_leftover_segments(const std::string& run_id,
                                                  const std::string& shm_dir = "/dev/shm");

}  // namespace cover::launch

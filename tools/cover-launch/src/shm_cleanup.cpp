#include "cover/launch/shm_cleanup.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace cover::launch {
namespace {

// True when `run_id` occurs in `name` with no letter or digit right before or after it:
// run "demo_12" must not take "cover_demo_123" of another run that is still alive.
bool names_run(const std::string& name, const std::string& run_id) {
  const auto is_alnum = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
  for (auto at = name.find(run_id); at != std::string::npos; at = name.find(run_id, at + 1)) {
    const auto end = at + run_id.size();
    const bool starts_clean = at == 0 || !is_alnum(name[at - 1]);
    const bool ends_clean = end == name.size() || !is_alnum(name[end]);
    if (starts_clean && ends_clean) return true;
  }
  return false;
}

}  // namespace

std::vector<std::string> remove_leftover_segments(const std::string& run_id,
                                                  const std::string& shm_dir) {
  std::vector<std::string> removed;
  if (run_id.size() < 3) return removed;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(shm_dir, error)) {
    const std::string name = entry.path().filename().string();
    if (!names_run(name, run_id)) continue;
    std::error_code remove_error;
    std::filesystem::remove_all(entry.path(), remove_error);
    if (!remove_error) removed.push_back(name);
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

}  // namespace cover::launch

#include "cover/vocabulary/task.hpp"

#include <algorithm>
#include <cctype>

namespace cover::mission {

std::vector<int> Task::ugvs() const {
  std::vector<int> ids;
  for (const TransitionProcess& p : processes) {
    for (const int k : {p.from_ugv, p.to_ugv}) {
      if (std::find(ids.begin(), ids.end(), k) == ids.end()) ids.push_back(k);
    }
  }
  return ids;
}

bool is_valid_task_id(const std::string& id) {
  if (id.empty() || id.size() > kMaxTaskIdLength) return false;
  for (const char c : id) {
    const bool allowed = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
                         c == '.' || c == ':' || c == '@' || c == '/' || c == '+';
    if (!allowed) return false;
  }
  return true;
}

Task repeat_processes(const Task& task, int process_count) {
  Task repeated = task;
  repeated.processes.clear();
  if (task.processes.empty()) return repeated;
  for (int i = 0; i < process_count; ++i) {
    repeated.processes.push_back(
        task.processes[static_cast<std::size_t>(i) % task.processes.size()]);
  }
  return repeated;
}

}  // namespace cover::mission

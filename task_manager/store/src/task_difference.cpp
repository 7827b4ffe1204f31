#include "cover/task_manager/task_difference.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "cover/task_manager/task_json.hpp"

namespace cover::task_manager {
namespace {

using json = nlohmann::json;

std::string change(const std::string& field, const json& known, const json& submitted) {
  return field + " " + known.dump() + " -> " + submitted.dump();
}

// Every key of either process, in the order of the stored form (keys sorted).
void compare_process(std::size_t index, const json& known, const json& submitted,
                     std::vector<std::string>& out) {
  json keys = known;
  keys.update(submitted);
  const std::string prefix = "processes[" + std::to_string(index) + "].";
  for (const auto& item : keys.items()) {
    const std::string& key = item.key();
    const json a = known.value(key, json());
    const json b = submitted.value(key, json());
    if (a != b) out.push_back(change(prefix + key, a, b));
  }
}

}  // namespace

std::vector<std::string> task_differences(const mission::Task& known,
                                          const mission::Task& submitted) {
  const json a = json::parse(task_to_json(known));
  const json b = json::parse(task_to_json(submitted));
  std::vector<std::string> out;
  if (a["uav_id"] != b["uav_id"]) out.push_back(change("uav_id", a["uav_id"], b["uav_id"]));
  const json& pa = a["processes"];
  const json& pb = b["processes"];
  if (pa.size() != pb.size()) {
    out.push_back("processes: " + std::to_string(pa.size()) + " -> " + std::to_string(pb.size()));
  }
  for (std::size_t i = 0; i < std::min(pa.size(), pb.size()); ++i) {
    compare_process(i, pa[i], pb[i], out);
  }
  return out;
}

}  // namespace cover::task_manager

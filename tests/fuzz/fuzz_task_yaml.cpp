// The task YAML parser (cover submit FILE, cover-uav-agent --task FILE, scenarios' tasks).
// Contract: YAML syntax errors aside, load_task returns a task or throws ConfigError; a
// task it returns passes validation, is finite and within the documented bounds, and
// survives the trip to the wire and back unchanged.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "cover/config/config_error.hpp"
#include "cover/mission/task_file.hpp"
#include "cover/vocabulary/task.hpp"
#include "cover/wire/task.hpp"
#include "fuzz_input.hpp"

namespace {

using cover::fuzz::require;

constexpr int kUgvCount = 4;

void check_task(const cover::mission::Task& task) {
  require(cover::mission::is_valid_task_id(task.task_id), "accepted a bad task id");
  require(!task.processes.empty(), "accepted a task without processes");
  for (const auto& p : task.processes) {
    require(p.from_ugv >= 0 && p.from_ugv < kUgvCount && p.to_ugv >= 0 && p.to_ugv < kUgvCount,
            "accepted an unknown UGV");
    require(p.initial_point_m.allFinite() && p.transition_point_m.allFinite() &&
                p.final_point_m.allFinite(),
            "accepted a non-finite point");
    require(std::isfinite(p.vmax_m_s) && p.vmax_m_s > 0.0 && std::isfinite(p.amax_m_s2) &&
                p.amax_m_s2 > 0.0,
            "accepted a non-positive or non-finite limit");
  }
  const cover::mission::Task back = cover::wire::from_msg(cover::wire::to_msg(task, 0.0));
  require(back.task_id == task.task_id && back.uav_id == task.uav_id &&
              back.processes.size() == task.processes.size(),
          "the task changed on the wire");
  for (std::size_t i = 0; i < task.processes.size(); ++i) {
    const auto& a = task.processes[i];
    const auto& b = back.processes[i];
    require(a.from_ugv == b.from_ugv && a.to_ugv == b.to_ugv &&
                a.initial_point_m == b.initial_point_m &&
                a.transition_point_m == b.transition_point_m &&
                a.final_point_m == b.final_point_m && a.final_action == b.final_action &&
                a.vmax_m_s == b.vmax_m_s && a.amax_m_s2 == b.amax_m_s2 && a.method == b.method,
            "a process changed on the wire");
  }
  cover::mission::validate_task(back, kUgvCount);  // must not throw: it is the same task
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  YAML::Node node;
  try {
    node = YAML::Load(text);
  } catch (const YAML::Exception&) {
    return 0;  // load_task_file turns these into ConfigError (tested in tests/mission)
  }
  try {
    check_task(cover::mission::load_task(node, "fuzz.yaml", kUgvCount));
  } catch (const cover::config::ConfigError&) {
  } catch (const std::exception& e) {
    cover::fuzz::violated(std::string("not a ConfigError: ") + e.what());
  }
  return 0;
}

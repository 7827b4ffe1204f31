#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/vocabulary/task.hpp"

namespace cover::mission {

// A task as a file (or a YAML node) states it, and the checks every task passes before it
// is flown or queued, wherever it comes from (a file, the wire, the task store).

// One process from its YAML mapping; `default_method`: the task's `method:` key, for a
// process without its own.
TransitionProcess read_process(config::YamlReader& reader, const std::string& default_method = "");
// A task from its YAML mapping, not validated yet.
Task read_task(config::YamlReader& reader);

// Throws config::ConfigError naming the process and key when the task cannot be flown:
// no process, a UGV id outside [0, ugv_count), Gi == Gj, a chain break (process k+1 must
// start where process k ended), a non-finite or absurd point, non-positive limits, or a
// landing before the last process (the UAV would be disarmed for the rest of the task),
// an unknown method.
void validate_task(const Task& task, int ugv_count);

// Loads and validates a task from a YAML node / file. `context` names the source in errors.
Task load_task(const YAML::Node& node, const std::string& context, int ugv_count);
Task load_task_file(const std::string& path, int ugv_count);

}  // namespace cover::mission

#include "cover/task_manager/task_limits.hpp"

namespace cover::task_manager {

TaskLimits TaskLimits::load(config::YamlReader& reader) {
  TaskLimits limits;
  config::load_fields(limits, reader);
  limits.validate();
  return limits;
}

TaskLimits TaskLimits::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

TaskLimits TaskLimits::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader section =
      config::open_section(document, source, "task_manager", /*required=*/false);
  return load(section);
}

void TaskLimits::validate() const {
  const std::string ctx = "task_manager";
  // Each field's bounds, among them the vehicle's limits within what any task may have
  // (mission/motion_limits.hpp): above, the manager would promise tasks every UAV rejects.
  config::check_fields(*this, ctx);
  config::check(max_z_m > min_z_m, ctx + ".max_z_m", "must be above min_z_m");
  config::check(restart_grace_s >= heartbeat_timeout_s, ctx + ".restart_grace_s",
                "must be >= heartbeat_timeout_s");
}

}  // namespace cover::task_manager

#include "cover/task_manager/task_limits.hpp"

#include <cmath>

namespace cover::task_manager {
namespace {
bool positive(double value) {
  return std::isfinite(value) && value > 0.0;
}
}  // namespace

TaskLimits TaskLimits::load(config::YamlReader& reader) {
  TaskLimits limits;
  reader.optional("max_horizontal_m", limits.max_horizontal_m);
  reader.optional("min_z_m", limits.min_z_m);
  reader.optional("max_z_m", limits.max_z_m);
  reader.optional("max_vmax_m_s", limits.max_vmax_m_s);
  reader.optional("max_amax_m_s2", limits.max_amax_m_s2);
  reader.optional("heartbeat_timeout_s", limits.heartbeat_timeout_s);
  reader.optional("restart_grace_s", limits.restart_grace_s);
  reader.optional("dispatch_timeout_s", limits.dispatch_timeout_s);
  reader.reject_unknown_keys();
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
  config::check(positive(max_horizontal_m), ctx + ".max_horizontal_m", "must be > 0");
  config::check(std::isfinite(min_z_m), ctx + ".min_z_m", "must be a finite number");
  config::check(std::isfinite(max_z_m) && max_z_m > min_z_m, ctx + ".max_z_m",
                "must be a finite number above min_z_m");
  config::check(positive(max_vmax_m_s), ctx + ".max_vmax_m_s", "must be > 0");
  config::check(positive(max_amax_m_s2), ctx + ".max_amax_m_s2", "must be > 0");
  config::check(positive(heartbeat_timeout_s), ctx + ".heartbeat_timeout_s", "must be > 0");
  config::check(std::isfinite(restart_grace_s) && restart_grace_s >= heartbeat_timeout_s,
                ctx + ".restart_grace_s", "must be >= heartbeat_timeout_s");
  config::check(positive(dispatch_timeout_s), ctx + ".dispatch_timeout_s", "must be > 0");
}

}  // namespace cover::task_manager

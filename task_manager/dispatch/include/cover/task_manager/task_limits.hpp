#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/vocabulary/motion_limits.hpp"

namespace cover::task_manager {

// What the manager accepts and how long it waits (config/task_manager.yaml, section
// task_manager). The limits are the vehicle's and the field's, tighter than the sanity
// bounds of mission::Task::validate.
struct TaskLimits {
  double max_horizontal_m = 20.0;  // |x|, |y| of every point in its UGV frame
  double min_z_m = -0.5;
  double max_z_m = 10.0;
  double max_vmax_m_s = 3.0;         // the vehicle's speed limit
  double max_amax_m_s2 = 5.0;        // the vehicle's acceleration limit
  double heartbeat_timeout_s = 1.0;  // an agent / UGV IMU not heard for this long is "not up"
  // After a (re)start, a task in flight on an agent not heard yet is given this long before
  // it counts as silent: discovery of a restarted participant can take seconds. A
  // submission naming a vehicle not heard yet waits as long at most before it is judged.
  double restart_grace_s = 10.0;
  double dispatch_timeout_s = 5.0;  // a dispatched task the agent has not taken by then fails

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("max_horizontal_m", self.max_horizontal_m,
          Field("m", "|x|, |y| of every point in its UGV frame").above(0.0));
    visit("min_z_m", self.min_z_m, Field("m", "lowest z of every point"));
    visit("max_z_m", self.max_z_m, Field("m", "highest z of every point, above min_z_m"));
    visit(
        "max_vmax_m_s", self.max_vmax_m_s,
        Field("m/s", "the vehicle's speed limit").above(0.0).at_most(mission::kPlausibleVmax_m_s));
    visit("max_amax_m_s2", self.max_amax_m_s2,
          Field("m/s^2", "the vehicle's acceleration limit")
              .above(0.0)
              .at_most(mission::kPlausibleAmax_m_s2));
    visit("heartbeat_timeout_s", self.heartbeat_timeout_s,
          Field("s", "an agent or UGV IMU not heard for this long is not up").above(0.0));
    visit("restart_grace_s", self.restart_grace_s,
          Field("s",
                "after a (re)start, how long an unheard vehicle is waited for; "
                ">= heartbeat_timeout_s"));
    visit("dispatch_timeout_s", self.dispatch_timeout_s,
          Field("s", "a dispatched task the agent has not taken by then fails").above(0.0));
  }

  static TaskLimits load(config::YamlReader& reader);
  static TaskLimits load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static TaskLimits from_yaml(const YAML::Node& document, const std::string& source);
  // Throws config::ConfigError naming the key.
  void validate() const;
};

}  // namespace cover::task_manager

#include "cover/mission/task_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "cover/config/format_number.hpp"
#include "cover/vocabulary/method.hpp"

namespace cover::mission {
namespace {

// Points farther than this from the reference UGV are almost certainly a unit or sign
// mistake in the task (the UAV flies within a few metres of its UGVs).
constexpr double kMaxPointDistance_m = 100.0;

FinalAction parse_final_action(const std::string& text, const std::string& context) {
  if (text == "none") return FinalAction::None;
  if (text == "land") return FinalAction::Land;
  if (text == "deliver") return FinalAction::Deliver;
  throw config::ConfigError(context + ".final_action: '" + text +
                            "' is not one of none | land | deliver");
}

bool is_known_method(const std::string& method) {
  return method.empty() || sampc::parse_mode(method).has_value();
}

// The method as it is when printable ASCII, else only its length: a name from the wire
// goes into logs and the task store, where control bytes must not.
std::string unknown_method_message(const std::string& method) {
  const bool printable =
      std::all_of(method.begin(), method.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  const std::string shown =
      printable && method.size() <= 64
          ? "'" + method + "'"
          : "a " + std::to_string(method.size()) + "-byte name that is no method";
  return shown + " is not one of " + sampc::mode_names(" | ");
}

// The task's or the process's `method:` key, checked where it is written.
std::string read_method(config::YamlReader& reader, const std::string& default_method) {
  std::string method = default_method;
  reader.optional("method", method);
  if (!is_known_method(method)) {
    throw config::ConfigError(reader.context() + ".method: " + unknown_method_message(method) +
                              config::line_of(reader.node()["method"]));
  }
  return method;
}

void check_point(const Eigen::Vector3d& point, const std::string& context) {
  config::check(point.allFinite(), context, "must be finite numbers");
  config::check(point.norm() <= kMaxPointDistance_m, context,
                "is more than 100 m from its UGV (unit mistake?)");
}

// A NaN or infinity read from a file is reported where it is, with its line; the later
// validation (which also guards tasks from the wire) would only name the key.
void check_finite_at(const config::YamlReader& reader, const std::string& key, bool finite) {
  if (finite) return;
  throw config::ConfigError(reader.context() + "." + key + ": must be finite numbers" +
                            config::line_of(reader.node()[key]));
}

}  // namespace

TransitionProcess read_process(config::YamlReader& reader, const std::string& default_method) {
  TransitionProcess process;
  reader.require("from_ugv", process.from_ugv);
  reader.require("to_ugv", process.to_ugv);
  reader.require("initial_point_m", process.initial_point_m);
  reader.require("transition_point_m", process.transition_point_m);
  reader.require("final_point_m", process.final_point_m);
  std::string action = to_string(process.final_action);
  reader.optional("final_action", action);
  process.final_action = parse_final_action(action, reader.context());
  reader.optional("vmax_m_s", process.vmax_m_s);
  reader.optional("amax_m_s2", process.amax_m_s2);
  process.method = read_method(reader, default_method);
  reader.reject_unknown_keys();
  check_finite_at(reader, "initial_point_m", process.initial_point_m.allFinite());
  check_finite_at(reader, "transition_point_m", process.transition_point_m.allFinite());
  check_finite_at(reader, "final_point_m", process.final_point_m.allFinite());
  check_finite_at(reader, "vmax_m_s", std::isfinite(process.vmax_m_s));
  check_finite_at(reader, "amax_m_s2", std::isfinite(process.amax_m_s2));
  return process;
}

Task read_task(config::YamlReader& reader) {
  Task task;
  reader.optional("task_id", task.task_id);
  reader.optional("uav_id", task.uav_id);
  const std::string method = read_method(reader, "");
  YAML::Node list;
  reader.require("processes", list);
  config::check(list.IsSequence(), reader.context() + ".processes", "must be a list");
  for (std::size_t i = 0; i < list.size(); ++i) {
    config::YamlReader process_reader(list[i],
                                      reader.context() + ".processes[" + std::to_string(i) + "]");
    task.processes.push_back(read_process(process_reader, method));
  }
  reader.reject_unknown_keys();
  return task;
}

void validate_task(const Task& task, int ugv_count) {
  // An id a person can read back, that fits every string field of every DDS vendor, and
  // that a log or a terminal prints as it is.
  config::check(is_valid_task_id(task.task_id), "task_id",
                "must be 1.." + std::to_string(kMaxTaskIdLength) +
                    " characters of A-Z a-z 0-9 _ - . : @ / +");
  const std::string ctx = "task '" + task.task_id + "'";
  config::check(!task.processes.empty(), ctx + ".processes", "is empty: nothing to fly");
  config::check(task.uav_id >= 0, ctx + ".uav_id", "must be >= 0");
  for (std::size_t i = 0; i < task.processes.size(); ++i) {
    const TransitionProcess& p = task.processes[i];
    const std::string pctx = ctx + ".processes[" + std::to_string(i) + "]";
    config::check(p.from_ugv >= 0 && p.from_ugv < ugv_count, pctx + ".from_ugv",
                  "unknown UGV " + std::to_string(p.from_ugv) + " (there are " +
                      std::to_string(ugv_count) + ")");
    config::check(p.to_ugv >= 0 && p.to_ugv < ugv_count, pctx + ".to_ugv",
                  "unknown UGV " + std::to_string(p.to_ugv) + " (there are " +
                      std::to_string(ugv_count) + ")");
    config::check(p.from_ugv != p.to_ugv, pctx, "from_ugv and to_ugv must differ");
    if (i > 0) {
      config::check(p.from_ugv == task.processes[i - 1].to_ugv, pctx + ".from_ugv",
                    "must equal the previous process's to_ugv (the UAV is there)");
    }
    check_point(p.initial_point_m, pctx + ".initial_point_m");
    check_point(p.transition_point_m, pctx + ".transition_point_m");
    check_point(p.final_point_m, pctx + ".final_point_m");
    config::check(std::isfinite(p.vmax_m_s) && p.vmax_m_s > 0.0 && p.vmax_m_s <= kPlausibleVmax_m_s,
                  pctx + ".vmax_m_s",
                  "must be in (0, " + config::format_number(kPlausibleVmax_m_s) + "]");
    config::check(
        std::isfinite(p.amax_m_s2) && p.amax_m_s2 > 0.0 && p.amax_m_s2 <= kPlausibleAmax_m_s2,
        pctx + ".amax_m_s2", "must be in (0, " + config::format_number(kPlausibleAmax_m_s2) + "]");
    config::check(is_known_method(p.method), pctx + ".method", unknown_method_message(p.method));
    config::check(p.final_action != FinalAction::Land || i + 1 == task.processes.size(),
                  pctx + ".final_action", "land must be the last process (the UAV disarms)");
  }
}

Task load_task(const YAML::Node& node, const std::string& context, int ugv_count) {
  config::YamlReader reader(node, context);
  Task task = read_task(reader);
  validate_task(task, ugv_count);
  return task;
}

Task load_task_file(const std::string& path, int ugv_count) {
  return load_task(config::load_yaml_file(path), path, ugv_count);
}

}  // namespace cover::mission

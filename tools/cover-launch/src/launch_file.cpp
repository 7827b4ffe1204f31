#include "cover/launch/launch_file.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>

#include "cover/config/yaml_reader.hpp"
#include "cover/dds/security_options.hpp"
#include "cover/launch/dds_override.hpp"
#include "cover/launch/placeholders.hpp"
#include "cover/launch/process_count.hpp"

namespace cover::launch {
namespace {

constexpr int kMaxCpus = CPU_SETSIZE;  // what sched_setaffinity can name

bool only_chars(const std::string& text, const std::string& extra) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [&](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || extra.find(c) != std::string::npos;
  });
}

bool is_identifier(const std::string& text) {
  return only_chars(text, "_") && !std::isdigit(static_cast<unsigned char>(text[0]));
}

bool executable_named(const std::string& executable, const char* name) {
  return std::filesystem::path(executable).filename() == name;
}

// The flight-controller bridge: kept running by default in standing and field launches.
bool is_fc_bridge(const std::string& executable) {
  return executable_named(executable, "cover-fc-bridge");
}

// A process whose samples a flying UAV waits on: the UGV agents (IMU) and the motion-capture
// relay (relative states). Restarted after kSensorRespawnDelay_s by default.
bool is_sensor_agent(const std::string& executable) {
  return executable_named(executable, "cover-ugv-agent") ||
         executable_named(executable, "cover-mocap-relay");
}

// `respawn` and `keep_running` default by the launch's kind, `respawn_delay_s` by the
// process's role, where the file does not say.
void apply_defaults(ProcessSpec& spec, const config::YamlReader& process, LaunchKind kind) {
  if (!process.has("respawn")) spec.respawn.enabled = serves_until_stopped(kind) && !spec.ends_run;
  if (!process.has("keep_running")) {
    spec.keep_running = serves_until_stopped(kind) && is_fc_bridge(spec.executable);
  }
  if (!process.has("respawn_delay_s") && is_sensor_agent(spec.executable)) {
    spec.respawn.delay_s = kSensorRespawnDelay_s;
  }
}

// Every text of `spec` that `{i}` may appear in.
template <typename Visit>
void visit_texts(ProcessSpec& spec, Visit visit) {
  visit(spec.name);
  visit(spec.executable);
  for (auto& arg : spec.args) visit(arg);
  for (auto& [key, value] : spec.env) visit(value);
  visit(spec.netns);
  visit(spec.identity);
}

// The copies of a process with `count: N` (one without `count` stays one, and must not use
// `{i}`: nothing would replace it).
// `count` is nullopt when the file gives none.
std::vector<ProcessSpec> expand_count(ProcessSpec spec, std::optional<int> count,
                                      const std::string& label) {
  if (!count) {
    visit_texts(spec, [&](const std::string& text) {
      config::check(!uses_index(text), label,
                    "'" + text + "' uses {i}, the copy index, but the process has no count:");
    });
    return {spec};
  }
  config::check(*count >= 1 && *count <= kMaxProcessCount, label + ".count",
                std::to_string(*count) + " (valid: 1.." + std::to_string(kMaxProcessCount) + ")");
  config::check(*count == 1 || uses_index(spec.name), label + ".name",
                "'" + spec.name + "' must contain {i} with count: " + std::to_string(*count) +
                    " (each copy needs its own name)");
  std::vector<ProcessSpec> copies;
  for (int i = 0; i < *count; ++i) {
    ProcessSpec copy = spec;
    try {
      visit_texts(copy, [&](std::string& text) { text = substitute_index(text, i); });
    } catch (const std::invalid_argument& e) {
      throw config::ConfigError(label + ": " + e.what());
    }
    copies.push_back(std::move(copy));
  }
  return copies;
}

// `count:` as written: a number, or "{name}" of a launch variable whose value (the file's,
// or a --var flag's) is one. nullopt when the process has none.
std::optional<int> read_count(const config::YamlReader& process, const std::string& label,
                              const std::map<std::string, std::string>& variables) {
  if (!process.has("count")) return std::nullopt;
  const YAML::Node node = process.node()["count"];
  std::string text = node.IsScalar() ? node.Scalar() : "";
  std::string source;
  if (text.size() > 2 && text.front() == '{' && text.back() == '}') {
    const std::string name = text.substr(1, text.size() - 2);
    const auto variable = variables.find(name);
    config::check(variable != variables.end(), label + ".count",
                  "'" + text + "' names no variable of launch.variables");
    source = " (from {" + name + "})";
    text = variable->second;
  }
  const bool number = !text.empty() && text.size() <= 9 &&
                      text.find_first_not_of("-0123456789") == std::string::npos &&
                      text.find('-', 1) == std::string::npos && text != "-";
  config::check(number, label + ".count",
                "wrong type or value: '" + text + "'" + source + " is not a whole number");
  return std::stoi(text);
}

std::vector<ProcessSpec> parse_process(const YAML::Node& node, const std::string& context,
                                       LaunchKind kind,
                                       const std::map<std::string, std::string>& variables) {
  // Errors name the process as well as its index: "launch.processes[2] (ugv1)".
  std::string label = context;
  if (node.IsMap() && node["name"] && node["name"].IsScalar()) {
    label += " (" + node["name"].Scalar() + ")";
  }
  config::YamlReader process(node, label);
  ProcessSpec spec;
  process.require("name", spec.name);
  process.require("executable", spec.executable);
  process.optional("args", spec.args);
  process.optional("dds", spec.dds);
  process.optional("env", spec.env);
  process.optional("netns", spec.netns);
  process.optional("identity", spec.identity);
  process.optional("ends_run", spec.ends_run);
  process.optional("respawn", spec.respawn.enabled);
  process.optional("respawn_delay_s", spec.respawn.delay_s);
  process.optional("max_respawns", spec.respawn.max_respawns);
  process.optional("keep_running", spec.keep_running);
  process.optional("realtime_priority", spec.realtime_priority);
  process.optional("cpu_affinity", spec.cpu_affinity);
  YAML::Node count;
  process.optional("count", count);
  process.reject_unknown_keys();
  apply_defaults(spec, process, kind);
  return expand_count(std::move(spec), read_count(process, label, variables), label);
}

void validate_arguments(const ProcessSpec& spec, const std::set<std::string>& known) {
  for (const auto& arg : spec.args) {
    std::vector<std::string> names;
    try {
      names = placeholder_names(arg);
    } catch (const std::invalid_argument& e) {
      throw config::ConfigError("process '" + spec.name + "', argument '" + arg + "': " + e.what());
    }
    for (const auto& name : names) {
      config::check(known.count(name) > 0, "process '" + spec.name + "', argument '" + arg + "'",
                    "unknown placeholder {" + name + "} (declare it under launch.variables)");
    }
  }
}

}  // namespace

// A variable's value may use the built-in placeholders ({state_dir}/tasks.db), not other
// variables: one level of expansion, no order to define.
void check_variable_value(const std::string& key, const std::string& value) {
  const std::string context = "launch.variables." + key;
  std::vector<std::string> names;
  try {
    names = placeholder_names(value);
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(context + ": '" + value + "': " + e.what());
  }
  const auto& builtins = builtin_placeholders();
  for (const auto& name : names) {
    config::check(std::find(builtins.begin(), builtins.end(), name) != builtins.end(), context,
                  "'" + value + "' uses {" + name +
                      "}: a variable's value may use only the built-in placeholders");
  }
}

namespace {

void validate_respawn(const ProcessSpec& spec, const std::string& context) {
  const RespawnPolicy& respawn = spec.respawn;
  config::check(!(respawn.enabled && spec.ends_run), context,
                "respawn: true and ends_run: true exclude each other (the ends_run process's "
                "exit ends the run)");
  config::check(std::isfinite(respawn.delay_s) && respawn.delay_s >= 0.0, context,
                "respawn_delay_s must be a number of seconds >= 0");
  config::check(respawn.max_respawns >= 1, context, "max_respawns must be >= 1");
}

void validate_realtime_priority(const ProcessSpec& spec, const std::string& context) {
  config::check(spec.realtime_priority >= 0 && spec.realtime_priority <= 99, context,
                "realtime_priority must be 1..99 (SCHED_FIFO), or 0 for normal scheduling");
}

void validate_cpu_affinity(const ProcessSpec& spec, const std::string& context) {
  std::set<int> seen;
  for (const int cpu : spec.cpu_affinity) {
    config::check(cpu >= 0 && cpu < kMaxCpus, context,
                  "cpu_affinity: CPU " + std::to_string(cpu) + " (CPUs are numbered 0.." +
                      std::to_string(kMaxCpus - 1) + ")");
    config::check(seen.insert(cpu).second, context,
                  "cpu_affinity: CPU " + std::to_string(cpu) + " listed twice");
  }
}

void validate_keep_running(const ProcessSpec& spec, LaunchKind kind, const std::string& context) {
  if (!spec.keep_running) return;
  config::check(serves_until_stopped(kind), context,
                "keep_running: true needs launch.kind standing or field (a mission stops every "
                "process when it ends)");
  config::check(!spec.ends_run, context,
                "keep_running: true and ends_run: true exclude each other (the ends_run "
                "process's exit ends the run)");
}

void validate_process(const ProcessSpec& spec, const std::set<std::string>& known,
                      LaunchKind kind) {
  const std::string context = "process '" + spec.name + "'";
  config::check(only_chars(spec.name, "_-"), "process name '" + spec.name + "'",
                "use letters, digits, '_' and '-' only (it names the log file)");
  config::check(spec.name != "launch", context, "the name 'launch' is taken by launch.log");
  config::check(!spec.executable.empty(), context, "executable is empty");
  config::check(is_vendor(spec.dds), context, "dds: '" + spec.dds + "' (valid: fastdds, cyclone)");
  config::check(spec.netns.empty() || only_chars(spec.netns, "_-"), context,
                "netns: '" + spec.netns + "' (use letters, digits, '_' and '-')");
  for (const auto& [key, value] : spec.env) {
    config::check(is_identifier(key), context, "env: bad variable name '" + key + "'");
    config::check(key != "COVER_DDS" && key != "COVER_DDS_DOMAIN", context,
                  "env: " + key + " is set by the launcher (use dds: / --domain)");
    config::check(key != dds::kSecurityEnvironment && key != dds::kIdentityEnvironment, context,
                  "env: " + key + " is set by the launcher (use launch.security / identity:)");
  }
  validate_respawn(spec, context);
  validate_keep_running(spec, kind, context);
  validate_realtime_priority(spec, context);
  validate_cpu_affinity(spec, context);
  validate_arguments(spec, known);
}

}  // namespace

const std::vector<std::string>& builtin_placeholders() {
  static const std::vector<std::string> names{"run_dir", "run_id", "domain", "config_dir",
                                              "state_dir"};
  return names;
}

void LaunchFile::validate() const {
  config::check(only_chars(name, "_.-"), "launch.name '" + name + "'",
                "use letters, digits, '_', '.' and '-' only (it names the run folder)");
  config::check(std::isfinite(grace_period_s) && grace_period_s > 0.0, "launch.grace_period_s",
                "must be a positive number of seconds");
  config::check(!processes.empty(), "launch.processes", "no process to launch");
  std::set<std::string> known(builtin_placeholders().begin(), builtin_placeholders().end());
  for (const auto& [key, value] : variables) {
    config::check(is_identifier(key), "launch.variables", "bad variable name '" + key + "'");
    config::check(known.insert(key).second, "launch.variables",
                  "'" + key + "' is a built-in placeholder and cannot be redefined");
    check_variable_value(key, value);
  }
  std::set<std::string> names;
  int ends_run_count = 0;
  for (const auto& spec : processes) {
    validate_process(spec, known, kind);
    config::check(names.insert(spec.name).second, "launch.processes",
                  "duplicate process name '" + spec.name + "'");
    ends_run_count += spec.ends_run ? 1 : 0;
  }
  if (serves_until_stopped(kind)) {
    config::check(ends_run_count <= 1, "launch.processes",
                  std::string("at most one process may have ends_run: true in a ") +
                      to_string(kind) + " launch (found " + std::to_string(ends_run_count) + ")");
  } else {
    config::check(ends_run_count == 1, "launch.processes",
                  "exactly one process must have ends_run: true (found " +
                      std::to_string(ends_run_count) +
                      "); a standing or field launch (launch.kind) may have none");
  }
}

LaunchFile LaunchFile::parse(const YAML::Node& root_node, const std::string& context,
                             const std::string& directory,
                             const std::map<std::string, std::string>& overrides) {
  config::YamlReader root(root_node, context);
  config::check(root.has("launch"), context, "missing section 'launch'");
  config::YamlReader launch = root.child("launch");
  root.reject_unknown_keys();

  LaunchFile file;
  file.directory = directory;
  launch.require("name", file.name);
  std::string kind = to_string(file.kind);
  launch.optional("kind", kind);
  const auto parsed_kind = parse_launch_kind(kind);
  config::check(parsed_kind.has_value(), launch.context() + ".kind",
                "'" + kind + "' (valid: mission, standing, field)");
  file.kind = *parsed_kind;
  launch.optional("grace_period_s", file.grace_period_s);
  launch.optional("variables", file.variables);
  launch.optional("security", file.security);
  launch.optional("record", file.record);
  launch.optional("foxglove", file.foxglove);
  launch.optional("ground_station", file.ground_station);
  YAML::Node processes;
  launch.require("processes", processes);
  launch.reject_unknown_keys();
  config::check(processes.IsSequence(), launch.context() + ".processes",
                "expected a list of processes");
  // A count may name a variable: its value as the run will have it.
  auto variables = file.variables;
  for (const auto& [key, value] : overrides) {
    if (variables.count(key) > 0) variables[key] = value;
  }
  for (std::size_t i = 0; i < processes.size(); ++i) {
    for (auto& spec : parse_process(processes[i],
                                    launch.context() + ".processes[" + std::to_string(i) + "]",
                                    file.kind, variables)) {
      file.processes.push_back(std::move(spec));
    }
  }
  try {
    file.validate();
  } catch (const config::ConfigError& e) {
    throw config::ConfigError(context + ": " + e.what());
  }
  return file;
}

LaunchFile LaunchFile::load_file(const std::string& path,
                                 const std::map<std::string, std::string>& overrides) {
  const auto directory = std::filesystem::absolute(path).parent_path().string();
  return parse(config::load_yaml_file(path), path, directory, overrides);
}

}  // namespace cover::launch

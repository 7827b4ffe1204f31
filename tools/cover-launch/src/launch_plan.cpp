#include "cover/launch/launch_plan.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "cover/config/state_dir.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/security_options.hpp"
#include "cover/launch/ground_station_view.hpp"
#include "cover/launch/discovery_server.hpp"
#include "cover/launch/live_view.hpp"
#include "cover/launch/placeholders.hpp"
#include "cover/launch/recording.hpp"
#include "cover/launch/run_naming.hpp"
#include "cover/launch/security_identity.hpp"

namespace cover::launch {
namespace {

constexpr int kMaxDomainId = 232;  // the RTPS port formula overflows above 232

void apply_variables(LaunchFile& file, const std::map<std::string, std::string>& overrides) {
  for (const auto& [key, value] : overrides) {
    auto variable = file.variables.find(key);
    if (variable == file.variables.end()) {
      // A value for a variable no argument uses would be silently ignored.
      throw std::invalid_argument("the launch file declares no variable '" + key + "'");
    }
    try {
      check_variable_value(key, value);
    } catch (const config::ConfigError& e) {
      throw std::invalid_argument(std::string("--var: ") + e.what());
    }
    variable->second = value;
  }
}

bool uses_placeholder(const std::string& text, const std::string& name) {
  const auto names = placeholder_names(text);
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Whether any variable or argument names {state_dir}: only then must the user have one.
bool uses_state_dir(const LaunchFile& file) {
  for (const auto& [key, value] : file.variables) {
    if (uses_placeholder(value, "state_dir")) return true;
  }
  for (const auto& spec : file.processes) {
    for (const auto& arg : spec.args) {
      if (uses_placeholder(arg, "state_dir")) return true;
    }
  }
  return false;
}

// The variables' values with the built-in placeholders in them expanded.
void expand_variables(std::map<std::string, std::string>& variables,
                      const PlaceholderValues& builtins) {
  for (auto& [key, value] : variables) {
    value = expand_argument(value, builtins).value_or("");
  }
}

PlannedProcess plan_process(const ProcessSpec& spec, const PlaceholderValues& values, int domain_id,
                            const std::string& security_directory) {
  PlannedProcess planned;
  planned.name = spec.name;
  planned.executable = spec.executable;
  planned.args = expand_arguments(spec.args, values);
  planned.dds = spec.dds;
  planned.netns = spec.netns;
  planned.ends_run = spec.ends_run;
  planned.respawn = spec.respawn;
  planned.keep_running = spec.keep_running;
  const auto clock = values.find("clock");
  const bool lockstep = clock != values.end() && clock->second == "lockstep";
  (lockstep ? planned.realtime_priority_withheld : planned.realtime_priority) =
      spec.realtime_priority;
  (lockstep ? planned.cpu_affinity_withheld : planned.cpu_affinity) = spec.cpu_affinity;
  for (const auto& [key, value] : spec.env) planned.env.push_back(key + "=" + value);
  planned.env.push_back("COVER_DDS=" + spec.dds);
  planned.env.push_back("COVER_DDS_DOMAIN=" + std::to_string(domain_id));
  if (!security_directory.empty()) {
    planned.identity = launch_identity(spec.name, spec.executable, planned.args, spec.identity);
    planned.env.push_back(std::string(dds::kSecurityEnvironment) + "=" + security_directory);
    planned.env.push_back(std::string(dds::kIdentityEnvironment) + "=" + planned.identity);
  }
  return planned;
}

}  // namespace

LaunchPlan make_plan(LaunchFile file, const LaunchOptions& options) {
  if (options.domain_id < 0 || options.domain_id > kMaxDomainId) {
    throw std::invalid_argument("DDS domain " + std::to_string(options.domain_id) +
                                " is out of range (valid: 0.." + std::to_string(kMaxDomainId) +
                                ")");
  }
  apply_variables(file, options.variables);
  if (file.foxglove || options.foxglove) add_live_view(file);
  if (file.ground_station || options.ground_station) add_ground_station(file);
  if (file.record || options.record) add_recorder(file, recorder_executable());
  apply_dds_overrides(file.processes, options.dds_overrides);
  if (!options.dds_profile.empty()) {
    for (auto& process : file.processes) process.env["COVER_DDS_PROFILE"] = options.dds_profile;
    const std::string server = discovery_server_for(options.dds_profile, options.domain_id);
    if (!server.empty()) add_discovery_server(file, server);
  }

  LaunchPlan plan;
  plan.name = file.name;
  plan.kind = file.kind;
  plan.run_id = make_run_id(file.name, options.launcher_pid);
  plan.run_dir = std::filesystem::absolute(options.run_dir).lexically_normal().string();
  plan.launch_dir = file.directory;
  plan.domain_id = options.domain_id;
  plan.grace_period_s = file.grace_period_s;
  namespace fs = std::filesystem;
  if (!options.security_directory.empty()) {
    plan.security_directory = fs::absolute(options.security_directory).lexically_normal().string();
  } else if (!file.security.empty()) {
    plan.security_directory =
        (fs::path(file.directory) / file.security).lexically_normal().string();
  }

  PlaceholderValues builtins;
  builtins["run_dir"] = plan.run_dir;
  builtins["run_id"] = plan.run_id;
  builtins["domain"] = std::to_string(options.domain_id);
  builtins["config_dir"] = config::default_config_dir();
  if (uses_state_dir(file)) {
    plan.state_dir = config::default_state_dir();
    builtins["state_dir"] = plan.state_dir;
  }
  expand_variables(file.variables, builtins);
  plan.variables = file.variables;
  PlaceholderValues values(file.variables.begin(), file.variables.end());
  values.insert(builtins.begin(), builtins.end());
  for (const auto& spec : file.processes) {
    plan.processes.push_back(
        plan_process(spec, values, options.domain_id, plan.security_directory));
  }
  return plan;
}

}  // namespace cover::launch

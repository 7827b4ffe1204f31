// cover-launch: starts a whole local COVER system from a launch file, watches it and stops
// it in order. The logic is in the cover_launch library; this file is the command line.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "cover/config/config_error.hpp"
#include "cover/config/state_dir.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/security_check.hpp"
#include "cover/launch/exit_codes.hpp"
#include "cover/launch/hangup_guard.hpp"
#include "cover/launch/launch_plan.hpp"
#include "cover/launch/run_naming.hpp"
#include "cover/launch/run_report.hpp"
#include "cover/launch/supervisor.hpp"
#include "cover/logging/log.hpp"
#include "cover/startup/startup.hpp"

namespace {

using namespace cover::launch;

constexpr const char* kFooter = R"(
Launch file (YAML, see config/launch/example.yaml and docs/launch.md):
  launch:
    name: NAME               run folder runs/NAME_<date-time>, run id NAME_<pid>
    kind: mission            mission | standing | field (below)
    grace_period_s: 3.0      per signal when stopping: SIGINT, SIGTERM, then SIGKILL
    variables: {clock: lockstep, seed: ""}
    security: DIR            DDS-Security fleet directory (relative to the file; --security)
    processes:               started in order, stopped in reverse order
      - name: sim            log: <run_dir>/sim.log
        executable: cover-sim            bare: beside cover-launch, then $PATH
        args: ["--seed={seed}", "--run-id={run_id}"]
        dds: fastdds         fastdds | cyclone, given as $COVER_DDS
        env: {KEY: value}
        netns: cwifi-sim     run in this network namespace (ip netns exec; root)
        identity: sim        DDS-Security identity when secure (default: by role)
        ends_run: true       its exit ends the run (mission: exactly one; else at most one)
        respawn: false       restart it when it dies (not with ends_run); default: false in
                             a mission, true in a standing or field launch
        respawn_delay_s: 1.0 wait before each restart (>= 0)
        max_respawns: 10     then: mission: an unexpected death (exit 4); else: not restarted
        keep_running: false  standing/field: not stopped when the run ends by another
                             process's exit (default: true for cover-fc-bridge)
        realtime_priority: 0 SCHED_FIFO priority 1..99 (0: normal scheduling); needs root
                             or CAP_SYS_NICE; not applied when {clock} is lockstep
        cpu_affinity: [1]    pin it (and its threads) to these CPUs; not applied when {clock}
                             is lockstep
  Placeholders: {run_dir} {run_id} {domain} {config_dir} {state_dir} and every variable;
  an argument whose placeholder is empty is dropped. {{ and }} are literal braces. A
  variable's value may use the built-in ones ({state_dir}: $XDG_STATE_HOME/cover, else
  ~/.local/state/cover, created when used); --json and launch.log give every value.

Kinds: mission (default): any process that dies for good ends the run (exit 4). standing
  and field: a dying process is respawned by default; one that dies for good is logged and
  the others go on; only the ends_run process (if any) or a signal ends the run.
SIGHUP (the terminal closed, an SSH session dropped) stops nothing: it is logged and
  ignored, and every child runs in a session of its own. Stop a launch with SIGINT/SIGTERM.

Exit codes:
  0    run completed (the ends_run process exited with 0)
  1    an unexpected error in the launcher (its message on stderr)
  2    usage or launch-file error
  3    the ends_run process failed (non-zero exit)
  4    a process died unexpectedly or could not be started (standing/field: every
       process has ended for good)
  130  interrupted (SIGINT/SIGTERM to cover-launch))";

const CLI::Validator kNonNegativeInteger(
    [](std::string& text) {
      const bool digits =
          !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
      return digits ? std::string() : "expected a non-negative integer, got '" + text + "'";
    },
    "N");

struct Flags {
  std::string file;
  std::vector<std::string> dds;
  std::vector<std::string> vars;
  std::string clock;
  std::string seed;
  std::string run_dir;
  std::string security;
  std::string dds_profile;
  int domain_id = -1;
  bool json = false;
  bool record = false;
  bool foxglove = false;
  bool ground_station = false;
};

void add_flags(CLI::App& app, Flags& flags) {
  app.add_option("FILE", flags.file, "Launch file (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("--dds", flags.dds,
                 "NAME=VENDOR: process NAME (or a glob such as 'ugv*') on fastdds|cyclone; "
                 "repeatable, the later flag wins where globs overlap");
  app.add_option("--clock", flags.clock, "Sets variable {clock}")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  app.add_option("--seed", flags.seed, "Sets variable {seed}")->check(kNonNegativeInteger);
  app.add_option("--var", flags.vars, "KEY=VALUE: sets variable {KEY}; repeatable");
  app.add_option("--domain", flags.domain_id,
                 "DDS domain 0..232, given as $COVER_DDS_DOMAIN and {domain} "
                 "(default: $COVER_DDS_DOMAIN or 0)");
  app.add_option("--run-dir", flags.run_dir, "Run folder (default: runs/NAME_YYYYmmdd-HHMMSS)");
  app.add_option("--security", flags.security,
                 "DDS-Security fleet directory (cover security init): each process runs secure "
                 "with its identity by role (default: the file's launch.security, else plain)");
  app.add_option("--dds-profile", flags.dds_profile,
                 "config/dds.yaml profile for every process (default: $COVER_DDS_PROFILE); one "
                 "with a discovery_server (`server`) starts `fastdds discovery` first");
  app.add_flag("--record", flags.record,
               "Record every catalogued topic into <run_dir>/recording.mcap (as record: true; "
               "docs/recording.md)");
  app.add_flag("--foxglove", flags.foxglove,
               "Serve the run live to Foxglove on ws://HOST:8765 (as foxglove: true; "
               "docs/recording.md)");
  app.add_flag("--ground-station", flags.ground_station,
               "Serve the operator's page on http://127.0.0.1:8080 (as ground_station: true; its "
               "address with the token in <run_dir>/ground_station.log)");
  app.add_flag("--json", flags.json,
               "Print result.json plus processes, run_dir and exit_code as one JSON object");
}

int domain_from_environment() {
  const char* text = std::getenv("COVER_DDS_DOMAIN");
  if (!text || !*text) return 0;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0')
    throw std::invalid_argument(std::string("COVER_DDS_DOMAIN is not a number: ") + text);
  return static_cast<int>(value);
}

// The variables the flags set (--var, --clock, --seed).
std::map<std::string, std::string> flag_variables(const Flags& flags) {
  std::map<std::string, std::string> variables;
  for (const auto& text : flags.vars) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw std::invalid_argument("--var " + text + ": expected KEY=VALUE");
    }
    variables[text.substr(0, equals)] = text.substr(equals + 1);
  }
  if (!flags.clock.empty()) variables["clock"] = flags.clock;
  if (!flags.seed.empty()) variables["seed"] = flags.seed;
  return variables;
}

LaunchOptions make_options(const Flags& flags, const LaunchFile& file) {
  LaunchOptions options;
  for (const auto& text : flags.dds) options.dds_overrides.push_back(parse_dds_override(text));
  options.variables = flag_variables(flags);
  options.domain_id = flags.domain_id >= 0 ? flags.domain_id : domain_from_environment();
  options.run_dir = !flags.run_dir.empty()
                        ? flags.run_dir
                        : default_run_dir(std::filesystem::current_path().string(), file.name,
                                          std::chrono::system_clock::now());
  options.security_directory = flags.security;
  options.record = flags.record;
  options.foxglove = flags.foxglove;
  options.ground_station = flags.ground_station;
  options.dds_profile = cover::dds::profile_from_environment("");
  if (!flags.dds_profile.empty()) options.dds_profile = flags.dds_profile;
  options.launcher_pid = getpid();
  return options;
}

// A secure launch checks every process's identity, and that each runs the fleet's vendor,
// before starting any: one clear error instead of a process dying at start.
void check_security(const LaunchPlan& plan) {
  if (plan.security_directory.empty()) return;
  for (const auto& process : plan.processes) {
    cover::dds::ParticipantOptions options;
    options.vendor = cover::dds::parse_vendor(process.dds);
    options.security = {true, plan.security_directory, process.identity};
    try {
      cover::dds::check_participant_security(options);
    } catch (const std::exception& e) {
      throw std::invalid_argument("process '" + process.name + "': " + e.what());
    }
  }
}

// Creates the run folder with launch.log, removes a result.json of an earlier run there,
// which would otherwise be reported as this run's, and writes run.json (the run's identity,
// run_report.hpp) before any process starts. Creates the state directory when the launch
// uses it: a process must not fail on a folder missing on a fresh account.
void prepare_run_dir(const LaunchPlan& plan) {
  const std::filesystem::path dir = plan.run_dir;
  std::filesystem::create_directories(dir);
  cover::logging::add_file((dir / "launch.log").string());
  const auto stale = dir / "result.json";
  if (std::filesystem::remove(stale)) spdlog::warn("removed {} of an earlier run", stale.string());
  if (!plan.state_dir.empty()) cover::config::create_state_dir(plan.state_dir);
  // Written whole under another name, then renamed: a reader never sees half of it.
  const auto identity = dir / "run.json";
  const auto partial = dir / "run.json.partial";
  std::ofstream(partial) << make_identity(plan, getpid()).dump() << "\n";
  std::filesystem::rename(partial, identity);
}

// "clock=realtime db=/home/u/.local/state/cover/tasks.db": what the processes were given.
std::string variables_text(const LaunchPlan& plan) {
  std::string text;
  for (const auto& [key, value] : plan.variables) {
    text += (text.empty() ? "" : " ") + key + "=" + value;
  }
  return text.empty() ? "none" : text;
}

int run(const LaunchPlan& plan, bool json) {
  spdlog::info("launch {} ({}): run id {}, run dir {}, domain {}, DDS-Security {}", plan.name,
               to_string(plan.kind), plan.run_id, plan.run_dir, plan.domain_id,
               plan.security_directory.empty() ? "off" : plan.security_directory);
  spdlog::info("variables: {}{}", variables_text(plan),
               plan.state_dir.empty() ? "" : " (state directory " + plan.state_dir + ")");
  const RunOutcome outcome = supervise(plan);
  if (json) {
    std::cout << make_report(plan, outcome).dump() << std::endl;
  } else {
    std::cout << make_summary(plan, outcome) << std::flush;
  }
  return outcome.exit_code;
}

// Loads the launch file and runs it; the exit code.
int load_and_run(const Flags& flags) {
  LaunchPlan plan;
  try {
    const LaunchFile file = LaunchFile::load_file(flags.file, flag_variables(flags));
    plan = make_plan(file, make_options(flags, file));
    check_security(plan);
    prepare_run_dir(plan);
  } catch (const std::exception& e) {
    std::cerr << "cover-launch: " << e.what() << "\n";
    return kExitUsage;
  }
  return run(plan, flags.json);
}

}  // namespace

int main(int argc, char** argv) {
  HangupGuard::install();  // before any thread exists, before run_main's signal watcher
  Flags flags;
  cover::startup::Program program;
  program.name = "cover-launch";
  program.description = "cover-launch: start a local COVER system from a launch file";
  program.exit_codes = kFooter;
  program.logger_name = [] { return std::string("cover-launch"); };
  program.add_flags = [&](CLI::App& app) { add_flags(app, flags); };
  return cover::startup::run_main(argc, argv, program,
                                  [&](const CLI::App&) { return load_and_run(flags); });
}

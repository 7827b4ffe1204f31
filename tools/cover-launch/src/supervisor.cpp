#include "cover/launch/supervisor.hpp"

#include <signal.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "cover/launch/executable_lookup.hpp"
#include "cover/launch/exit_codes.hpp"
#include "cover/launch/shm_cleanup.hpp"
#include "cover/process/child_process.hpp"
#include "cover/process/cpu_list.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::launch {
namespace {

using std::chrono::milliseconds;
using std::chrono::steady_clock;

// How often the watch loop looks for exited children. A shutdown signal wakes it at once;
// an exit is noticed within this period, which is far below any grace period.
constexpr milliseconds kWatchPeriod{10};
// After SIGKILL the kernel reaps promptly; this bound only guards against a stuck wait.
constexpr milliseconds kKillWait{5000};

struct Child {
  std::size_t index = 0;  // in the plan
  const PlannedProcess* spec = nullptr;
  std::unique_ptr<process::ChildProcess> process;  // the latest run
  ProcessOutcome* outcome = nullptr;
  // Set while a dead respawning process waits for its restart. A deadline checked by the
  // watch loop, not a sleep: the others stay watched and a signal is still seen at once.
  std::optional<steady_clock::time_point> respawn_at;
  // Standing and field launches: died and not to be restarted; the others went on.
  bool ended = false;
};

std::string online_cpus() {
  const long count = sysconf(_SC_NPROCESSORS_ONLN);
  return count > 0 ? "0.." + std::to_string(count - 1) : "unknown";
}

std::string join(const std::vector<std::string>& words) {
  std::string line;
  for (const auto& word : words) line += (line.empty() ? "" : " ") + word;
  return line;
}

std::string describe_exit(const process::ChildProcess& process) {
  if (const int signal_number = process.killed_by_signal()) {
    return "killed by signal " + std::to_string(signal_number) + " (" + strsignal(signal_number) +
           ")";
  }
  return "exit code " + std::to_string(process.exit_code().value_or(-1));
}

// "1.0", "0.25": seconds with at least one decimal, as a launch file writes them.
std::string seconds_text(double seconds) {
  std::string text = fmt::format("{:.3f}", seconds);
  while (text.back() == '0' && text[text.size() - 2] != '.') text.pop_back();
  return text;
}

// Polls once; true once the child has exited, its exit code then recorded. Silent, so
// that the caller can log a death as final or as one to respawn.
bool poll_exit(Child& child) {
  if (child.outcome->exit_code) return true;
  if (!child.process->wait(milliseconds(0))) return false;
  child.outcome->exit_code = child.process->exit_code();
  child.outcome->cpu_s = child.process->cpu_s();
  child.outcome->max_rss_kib = child.process->max_rss_kib();
  return true;
}

void log_exit(const Child& child) {
  spdlog::info("{} (pid {}) exited: {}", child.spec->name, child.process->pid(),
               describe_exit(*child.process));
}

// Polls once; records and logs the exit the first time it is seen.
bool has_exited(Child& child) {
  if (child.outcome->exit_code) return true;
  if (!poll_exit(child)) return false;
  log_exit(child);
  return true;
}

bool may_respawn(const Child& child) {
  const RespawnPolicy& policy = child.spec->respawn;
  return policy.enabled && child.outcome->respawns < policy.max_respawns;
}

// SIGINT, grace, SIGTERM, grace, SIGKILL. SIGKILL goes to the child's process group, so
// helpers it started cannot outlive the run either.
void stop(Child& child, milliseconds grace) {
  if (has_exited(child)) return;
  const pid_t pid = child.process->pid();
  for (const int signal_number : {SIGINT, SIGTERM}) {
    child.outcome->stopped_by = signal_number == SIGINT ? "SIGINT" : "SIGTERM";
    spdlog::info("stopping {} (pid {}): {}", child.spec->name, pid, child.outcome->stopped_by);
    kill(pid, signal_number);
    if (child.process->wait(grace) && has_exited(child)) return;
  }
  child.outcome->stopped_by = "SIGKILL";
  spdlog::warn("stopping {} (pid {}): SIGKILL, it ignored SIGINT and SIGTERM for {} ms",
               child.spec->name, pid, 2 * grace.count());
  killpg(pid, SIGKILL);
  kill(pid, SIGKILL);  // in case the child left its group (setsid)
  child.process->wait(kKillWait);
  has_exited(child);
}

class Supervisor {
 public:
  Supervisor(const LaunchPlan& plan, RunOutcome& outcome) : plan_(plan), outcome_(outcome) {
    for (const auto& spec : plan.processes) {
      ProcessOutcome process;
      process.name = spec.name;
      process.dds = spec.dds;
      outcome_.processes.push_back(process);
    }
  }

  void run() {
    if (resolve_all() && start_all()) watch();
    if (keep_some_running()) {
      stop_all(/*spare_keepers=*/true);
      hold_keepers();
    }
    stop_all(/*spare_keepers=*/false);
    remove_leftovers();
    spdlog::info("run over: {} (exit code {})", outcome_.reason, outcome_.exit_code);
  }

 private:
  void finish(int exit_code, const std::string& reason) {
    outcome_.exit_code = exit_code;
    outcome_.reason = reason;
  }

  // Every executable is found before anything starts: a typo must not leave half a system.
  bool resolve_all() {
    const std::string self_dir = self_executable_dir();
    const char* path = std::getenv("PATH");
    for (const auto& spec : plan_.processes) {
      auto resolved =
          resolve_executable(spec.executable, plan_.launch_dir, self_dir, path ? path : "");
      if (!resolved) {
        const bool is_path = spec.executable.find('/') != std::string::npos;
        spdlog::error(
            "{}: executable '{}' not found (looked {})", spec.name, spec.executable,
            is_path ? "relative to " + plan_.launch_dir : "in " + self_dir + ", then $PATH");
        finish(kExitProcessDied,
               spec.name + " could not be started: " + spec.executable + " not found");
        return false;
      }
      executables_.push_back(*resolved);
    }
    return resolve_ip();
  }

  // `ip` runs a process in a network namespace: it enters the namespace and execs the
  // command, so the pid the launcher watches and signals is the process's own.
  bool resolve_ip() {
    bool needed = false;
    for (const auto& spec : plan_.processes) needed = needed || !spec.netns.empty();
    if (!needed) return true;
    const char* path = std::getenv("PATH");
    const auto ip =
        resolve_executable("ip", "", "", std::string(path ? path : "") + ":/usr/sbin:/sbin");
    if (!ip) {
      spdlog::error("'ip' (iproute2) not found: needed for processes with a netns");
      finish(kExitProcessDied, "ip not found for netns");
      return false;
    }
    ip_ = *ip;
    return true;
  }

  bool start_all() {
    for (std::size_t i = 0; i < plan_.processes.size(); ++i) {
      if (process::ShutdownSignal::requested()) return true;  // watch() reports it
      if (!start(i)) return false;
    }
    return true;
  }

  std::vector<std::string> argv_of(std::size_t index) const {
    std::vector<std::string> argv;
    const std::string& netns = plan_.processes[index].netns;
    if (!netns.empty()) argv = {ip_, "netns", "exec", netns};
    argv.push_back(executables_[index]);
    const auto& args = plan_.processes[index].args;
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  }

  // A restart appends to the log, which holds why the earlier run died.
  std::unique_ptr<process::ChildProcess> spawn(std::size_t index, bool restart) const {
    const PlannedProcess& spec = plan_.processes[index];
    process::SpawnOptions options;
    options.extra_env = spec.env;
    options.log_file = (std::filesystem::path(plan_.run_dir) / (spec.name + ".log")).string();
    options.append_log = restart;
    options.null_stdin = true;
    // A session of its own: a hang-up of the launcher's terminal (SIGHUP to that session)
    // cannot reach it, nor a Ctrl-C there; the launcher stops it in its own order.
    options.new_session = true;
    options.ignore_hangup = true;
    options.close_other_fds = true;
    options.realtime_priority = spec.realtime_priority;
    options.cpu_affinity = spec.cpu_affinity;
    auto child = std::make_unique<process::ChildProcess>(argv_of(index), options);
    log_scheduling(spec, *child);
    return child;
  }

  static void log_affinity(const PlannedProcess& spec, const process::ChildProcess& child) {
    if (!spec.cpu_affinity_withheld.empty()) {
      spdlog::info("{}: cpu_affinity {} not applied in lockstep (a core taken from the others)",
                   spec.name, process::cpu_list(spec.cpu_affinity_withheld));
    }
    if (spec.cpu_affinity.empty()) return;
    const std::vector<int> cpus = child.cpus();
    if (cpus == spec.cpu_affinity) {
      spdlog::info("{} runs on CPU {}", spec.name, process::cpu_list(cpus));
    } else {
      spdlog::warn(
          "{}: cpu_affinity {} not applied as asked (this machine has CPUs {}): runs on {}",
          spec.name, process::cpu_list(spec.cpu_affinity), online_cpus(), process::cpu_list(cpus));
    }
  }

  static void log_scheduling(const PlannedProcess& spec, const process::ChildProcess& child) {
    if (spec.realtime_priority_withheld > 0) {
      spdlog::info(
          "{}: realtime_priority {} not applied: a lockstep run never sleeps and would "
          "starve the machine",
          spec.name, spec.realtime_priority_withheld);
    }
    log_affinity(spec, child);
    if (spec.realtime_priority == 0) return;
    if (child.realtime()) {
      spdlog::info("{} runs SCHED_FIFO priority {}", spec.name, spec.realtime_priority);
    } else {
      spdlog::warn(
          "{}: SCHED_FIFO priority {} refused (needs root, CAP_SYS_NICE or an rtprio "
          "limit in /etc/security/limits.conf): normal scheduling",
          spec.name, spec.realtime_priority);
    }
  }

  bool start(std::size_t index) {
    const PlannedProcess& spec = plan_.processes[index];
    try {
      auto child = spawn(index, /*restart=*/false);
      outcome_.processes[index].pid = child->pid();
      outcome_.processes[index].realtime_priority = child->realtime() ? spec.realtime_priority : 0;
      if (!spec.cpu_affinity.empty()) outcome_.processes[index].cpus = child->cpus();
      spdlog::info("started {} pid {} dds {}: {}", spec.name, child->pid(), spec.dds,
                   join(argv_of(index)));
      children_.push_back({index, &spec, std::move(child), &outcome_.processes[index], {}});
      return true;
    } catch (const std::exception& e) {
      spdlog::error("{}: {}", spec.name, e.what());
      finish(kExitProcessDied, spec.name + " could not be started: " + e.what());
      return false;
    }
  }

  void watch() {
    while (true) {
      if (process::ShutdownSignal::requested()) {
        spdlog::warn("interrupted: stopping every process");
        finish(kExitInterrupted, "interrupted by a signal");
        return;
      }
      for (auto& child : children_) {
        if (!watch_one(child, /*holding=*/false)) return;
      }
      if (all_ended()) {
        finish(kExitProcessDied, "every process has ended");
        spdlog::error("{}", outcome_.reason);
        return;
      }
      process::ShutdownSignal::wait_for(kWatchPeriod);
    }
  }

  // One look at one child: a due respawn, or an exit. False when the run is over. While
  // `holding` (the run is over, keep_running processes go on) no death ends anything.
  bool watch_one(Child& child, bool holding) {
    if (child.ended) return true;
    if (child.respawn_at) return steady_clock::now() < *child.respawn_at || respawn(child);
    if (!poll_exit(child)) return true;
    if (may_respawn(child)) {
      schedule_respawn(child);
      return true;
    }
    log_exit(child);
    if (holding || (serves_until_stopped(plan_.kind) && !child.spec->ends_run)) {
      end_for_good(child);
      return true;
    }
    judge_exit(child);
    return false;
  }

  // Standing and field launches: a process that dies without a restart left is logged, and
  // the others go on (ros2 launch's way); only the ends_run process ends the run.
  void end_for_good(Child& child) {
    child.ended = true;
    const std::string why =
        child.spec->respawn.enabled
            ? "max_respawns " + std::to_string(child.spec->respawn.max_respawns) + " used up"
            : "respawn: false";
    spdlog::error("{} (pid {}) died: {}; not restarted ({}); the other processes go on",
                  child.spec->name, child.process->pid(), describe_exit(*child.process), why);
  }

  bool all_ended() const {
    for (const auto& child : children_) {
      if (!child.ended) return false;
    }
    return !children_.empty();
  }

  bool is_keeper(const Child& child) const {
    return serves_until_stopped(plan_.kind) && child.spec->keep_running && !child.ended;
  }

  // After a run that ended without a signal to the launcher, keep_running processes go on.
  bool keep_some_running() const {
    if (outcome_.exit_code == kExitInterrupted || outcome_.reason.empty()) return false;
    for (const auto& child : children_) {
      if (is_keeper(child)) return true;
    }
    return false;
  }

  // Watches (and respawns) the keep_running processes until a signal reaches the launcher
  // or none is left. The run's exit code stays that of its end.
  void hold_keepers() {
    std::string names;
    for (const auto& child : children_) {
      if (is_keeper(child)) names += (names.empty() ? "" : ", ") + child.spec->name;
    }
    spdlog::warn(
        "{} keep running (keep_running: true) after the run's end: {}; stop with SIGINT "
        "or SIGTERM",
        names, outcome_.reason);
    while (true) {
      if (process::ShutdownSignal::requested()) {
        spdlog::warn("interrupted: stopping {}", names);
        outcome_.reason += "; then " + names + " stopped by a signal";
        return;
      }
      bool any_left = false;
      for (auto& child : children_) {
        if (!is_keeper(child)) continue;
        watch_one(child, /*holding=*/true);
        any_left = any_left || !child.ended;
      }
      if (!any_left) return;
      process::ShutdownSignal::wait_for(kWatchPeriod);
    }
  }

  void schedule_respawn(Child& child) {
    const RespawnPolicy& policy = child.spec->respawn;
    spdlog::warn("{} (pid {}) died: {}; respawning in {} s ({} of {})", child.spec->name,
                 child.process->pid(), describe_exit(*child.process), seconds_text(policy.delay_s),
                 child.outcome->respawns + 1, policy.max_respawns);
    child.respawn_at = steady_clock::now() + std::chrono::duration_cast<steady_clock::duration>(
                                                 std::chrono::duration<double>(policy.delay_s));
  }

  // Same argv and environment as the first start. False when the restart itself fails,
  // which ends a mission as a process that could not be started.
  bool respawn(Child& child) {
    child.respawn_at.reset();
    const std::string& name = child.spec->name;
    try {
      child.process = spawn(child.index, /*restart=*/true);
    } catch (const std::exception& e) {
      spdlog::error("{}: {}", name, e.what());
      if (serves_until_stopped(plan_.kind) && !child.spec->ends_run) {
        child.ended = true;  // the others go on, as after any final death
        spdlog::error("{} could not be restarted; the other processes go on", name);
        return true;
      }
      finish(kExitProcessDied, name + " could not be restarted: " + e.what());
      return false;
    }
    child.outcome->pid = child.process->pid();
    child.outcome->exit_code.reset();
    child.outcome->cpu_s.reset();
    ++child.outcome->respawns;
    spdlog::info("started {} pid {} (respawn {})", name, child.process->pid(),
                 child.outcome->respawns);
    return true;
  }

  void judge_exit(const Child& child) {
    const std::string how = describe_exit(*child.process);
    if (child.spec->ends_run && child.outcome->exit_code == 0) {
      finish(kExitCompleted, child.spec->name + " completed the run");
    } else if (child.spec->ends_run) {
      finish(kExitEndsRunFailed, child.spec->name + " failed: " + how);
      spdlog::error("{} ended the run with a failure: {}", child.spec->name, how);
    } else {
      // A respawning process gets here only once max_respawns restarts are used up.
      const std::string used_up =
          child.spec->respawn.enabled
              ? " (max_respawns " + std::to_string(child.spec->respawn.max_respawns) + " used up)"
              : "";
      finish(kExitProcessDied, child.spec->name + " (pid " + std::to_string(child.process->pid()) +
                                   ") died unexpectedly: " + how + used_up);
      spdlog::error("{}", outcome_.reason);
    }
  }

  // In reverse start order. `spare_keepers`: all but the keep_running processes.
  void stop_all(bool spare_keepers) {
    const milliseconds grace(static_cast<long>(plan_.grace_period_s * 1000.0));
    for (auto child = children_.rbegin(); child != children_.rend(); ++child) {
      if (spare_keepers && is_keeper(*child)) continue;
      if (child->respawn_at) {
        spdlog::info("{}: waiting for its respawn, not restarted", child->spec->name);
        child->respawn_at.reset();
      }
      stop(*child, grace);  // a dead one is only recorded
    }
  }

  void remove_leftovers() {
    outcome_.leftover_segments = remove_leftover_segments(plan_.run_id);
    for (const auto& name : outcome_.leftover_segments) {
      spdlog::warn("leftover segment removed: /dev/shm/{} (a process of the run left it behind)",
                   name);
    }
  }

  const LaunchPlan& plan_;
  RunOutcome& outcome_;
  std::vector<std::string> executables_;
  std::string ip_;  // iproute2, when a process runs in a network namespace
  std::vector<Child> children_;
};

}  // namespace

RunOutcome supervise(const LaunchPlan& plan) {
  RunOutcome outcome;
  Supervisor(plan, outcome).run();
  return outcome;
}

}  // namespace cover::launch

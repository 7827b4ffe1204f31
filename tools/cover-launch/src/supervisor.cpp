#include "cover/launch/supervisor.hpp"

#include <signal.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "cover/launch/executable_lookup.hpp"
#include "cover/launch/exit_codes.hpp"
#include "cover/launch/shm_cleanup.hpp"
#include "cover/process/child_process.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::launch {
namespace {

using std::chrono::milliseconds;

// How often the watch loop looks for exited children. A shutdown signal wakes it at once;
// an exit is noticed within this period, which is far below any grace period.
constexpr milliseconds kWatchPeriod{10};
// After SIGKILL the kernel reaps promptly; this bound only guards against a stuck wait.
constexpr milliseconds kKillWait{5000};

struct Child {
  const PlannedProcess* spec = nullptr;
  std::unique_ptr<process::ChildProcess> process;
  ProcessOutcome* outcome = nullptr;
};

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

// Polls once; records and logs the exit the first time it is seen.
bool has_exited(Child& child) {
  if (child.outcome->exit_code) return true;
  if (!child.process->wait(milliseconds(0))) return false;
  child.outcome->exit_code = child.process->exit_code();
  spdlog::info("{} (pid {}) exited: {}", child.spec->name, child.process->pid(),
               describe_exit(*child.process));
  return true;
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
    stop_all();
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
    return true;
  }

  bool start_all() {
    for (std::size_t i = 0; i < plan_.processes.size(); ++i) {
      if (process::ShutdownSignal::requested()) return true;  // watch() reports it
      if (!start(i)) return false;
    }
    return true;
  }

  bool start(std::size_t index) {
    const PlannedProcess& spec = plan_.processes[index];
    std::vector<std::string> argv{executables_[index]};
    argv.insert(argv.end(), spec.args.begin(), spec.args.end());
    process::SpawnOptions options;
    options.extra_env = spec.env;
    options.log_file = (std::filesystem::path(plan_.run_dir) / (spec.name + ".log")).string();
    options.null_stdin = true;
    options.new_process_group = true;
    options.close_other_fds = true;
    try {
      auto child = std::make_unique<process::ChildProcess>(argv, options);
      outcome_.processes[index].pid = child->pid();
      spdlog::info("started {} pid {} dds {}: {}", spec.name, child->pid(), spec.dds, join(argv));
      children_.push_back({&spec, std::move(child), &outcome_.processes[index]});
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
        if (has_exited(child)) return judge_exit(child);
      }
      process::ShutdownSignal::wait_for(kWatchPeriod);
    }
  }

  void judge_exit(const Child& child) {
    const std::string how = describe_exit(*child.process);
    if (child.spec->ends_run && child.outcome->exit_code == 0) {
      finish(kExitCompleted, child.spec->name + " completed the run");
    } else if (child.spec->ends_run) {
      finish(kExitEndsRunFailed, child.spec->name + " failed: " + how);
      spdlog::error("{} ended the run with a failure: {}", child.spec->name, how);
    } else {
      finish(kExitProcessDied, child.spec->name + " (pid " + std::to_string(child.process->pid()) +
                                   ") died unexpectedly: " + how);
      spdlog::error("{}", outcome_.reason);
    }
  }

  void stop_all() {
    const milliseconds grace(static_cast<long>(plan_.grace_period_s * 1000.0));
    for (auto child = children_.rbegin(); child != children_.rend(); ++child) stop(*child, grace);
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
  std::vector<Child> children_;
};

}  // namespace

RunOutcome supervise(const LaunchPlan& plan) {
  RunOutcome outcome;
  Supervisor(plan, outcome).run();
  return outcome;
}

}  // namespace cover::launch

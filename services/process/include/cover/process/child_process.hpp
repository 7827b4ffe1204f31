#pragma once

#include <sys/types.h>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cover::process {

// How a child is started beyond its argv. The defaults give the parent's stdin, stdout,
// stderr and process group.
struct SpawnOptions {
  // "KEY=value", laid over the parent's environment: an entry replaces the parent's value of
  // its key (and a later entry an earlier one), so the child's getenv() sees it.
  std::vector<std::string> extra_env;
  bool capture_stdout = false;  // a pipe read with ChildProcess::read_line
  // Truncated and opened in the child for stderr, and for stdout unless it is captured: a
  // supervisor keeps one log per process without relaying bytes itself.
  std::string log_file;
  // Appends to log_file instead of truncating it (O_APPEND): a restarted process adds its
  // lines after those of its earlier run, which tell why it died.
  bool append_log = false;
  bool null_stdin = false;  // stdin from /dev/null (a child in its own group must not read the tty)
  // The child leads a new process group, so a Ctrl-C at the terminal reaches only the
  // parent, which then stops its children in its own order.
  bool new_process_group = false;
  // The child leads a new session (setsid; a new process group too), with no controlling
  // terminal: closing the terminal or dropping the SSH session the parent runs in sends
  // SIGHUP to that terminal's session, which then cannot reach the child.
  bool new_session = false;
  // SIGHUP ignored in the child (an ignored disposition survives exec): a process that opens
  // a serial port as a session leader would otherwise get that port as its controlling
  // terminal, and die of SIGHUP when the cable is pulled.
  bool ignore_hangup = false;
  // Only stdin, stdout and stderr reach the child: open files of the parent (a log it
  // writes, a test harness's pipes) must not be held open by every process it starts.
  bool close_other_fds = false;
  // SCHED_FIFO at this priority (1..99) for the child and every thread it starts; 0: the
  // parent's policy. Refused without root, CAP_SYS_NICE or an rtprio limit: the child then
  // runs with the parent's policy (see ChildProcess::realtime()).
  int realtime_priority = 0;
  // The CPUs the child and every thread it starts may run on; empty: the parent's. A
  // control process whose DDS receive thread wakes its control thread is faster on one
  // core: a wake-up across cores is an inter-processor interrupt, which a VM makes costly
  // (realtime Scenario 2 on this VM: p50 0.22-0.32 -> 0.15-0.17 ms with the UAV agent on
  // one CPU). CPUs the machine does not have are ignored; if none is left, not applied
  // (see ChildProcess::cpus()).
  std::vector<int> cpu_affinity;
};

// A child process (fork + execve), for integration tests, benchmarks and launchers that run
// real processes. Its stdout can be read line by line; the destructor terminates it.
//
// The child dies with its parent: it is sent SIGKILL when the parent exits, also when the
// parent is killed or crashes (PR_SET_PDEATHSIG), so an aborted test or launcher leaves
// nothing running. Linux sends that signal when the *thread* that started the child ends:
// start children from the main thread, or from a thread that outlives them.
class ChildProcess {
 public:
  // `argv[0]` is the executable path. `extra_env` entries ("KEY=value") replace the
  // parent's values of their keys, or are added. Throws std::runtime_error when the child cannot be
  // started (no such executable, a log file that cannot be opened), naming why.
  ChildProcess(const std::vector<std::string>& argv, const std::vector<std::string>& extra_env = {},
               bool capture_stdout = false);
  ChildProcess(const std::vector<std::string>& argv, const SpawnOptions& options);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }

  // Reads one line from the child's stdout (capture_stdout only); nullopt on EOF/timeout.
  std::optional<std::string> read_line(std::chrono::milliseconds timeout);

  // Sends SIGTERM (or `signal`) and waits up to `timeout`, then SIGKILL. Returns the exit
  // code, or 128 + signal number if it was killed by a signal.
  int terminate(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000),
                int signal_number = 15);

  // Waits for the child to exit by itself; nullopt on timeout. A zero timeout only polls.
  std::optional<int> wait(std::chrono::milliseconds timeout);

  // The exit code once wait() or terminate() has seen the child exit.
  std::optional<int> exit_code() const { return exit_code_; }
  // The signal that killed the child, once it has exited; 0 when it exited by itself (the
  // exit code 128 + N alone cannot tell `exit(130)` from death by SIGINT).
  int killed_by_signal() const { return killed_by_signal_; }
  // CPU time the child used (user + system, its own threads and its reaped children),
  // seconds, once wait() or terminate() has seen it exit.
  std::optional<double> cpu_s() const { return cpu_s_; }
  // Its peak resident memory (ru_maxrss), KiB, once wait() or terminate() has seen it exit.
  std::optional<std::int64_t> max_rss_kib() const { return max_rss_kib_; }
  // Whether the child runs SCHED_FIFO (asked for with SpawnOptions::realtime_priority).
  bool realtime() const;
  // The CPUs the child may run on, ascending (empty when it cannot be read).
  std::vector<int> cpus() const;

 private:
  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  std::string buffer_;
  std::optional<int> exit_code_;
  int killed_by_signal_ = 0;
  std::optional<double> cpu_s_;
  std::optional<std::int64_t> max_rss_kib_;
};

}  // namespace cover::process

#include "cover/process/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <initializer_list>
#include <stdexcept>
#include <thread>

#include "cover/process/cpu_list.hpp"

extern char** environ;

namespace cover::process {

namespace {

// What the child needs, all allocated before the fork: after it the child calls only
// async-signal-safe functions (the parent may have other threads, holding locks).
struct ChildSetup {
  std::vector<char*> args;
  std::vector<char*> env;
  const SpawnOptions* options = nullptr;
  int stdout_fd = -1;  // write end of the stdout pipe, when captured
  int error_fd = -1;   // where the child writes its errno when it cannot exec
  pid_t parent = -1;
};

// "KEY" of "KEY=value" (the whole entry when it has no '=').
std::string env_key(const std::string& entry) {
  return entry.substr(0, entry.find('='));
}

// The parent's environment with `extra` laid over it: an extra entry replaces every entry
// of the parent's with its key, and a later extra entry an earlier one. Appended instead, a
// key would be there twice and getenv(), which returns the first, would give the child the
// parent's value: a launcher's COVER_DDS_DOMAIN lost to the one the user exported.
std::vector<std::string> child_environment(const std::vector<std::string>& extra) {
  std::vector<std::string> env;
  for (char** entry = environ; *entry; ++entry) env.emplace_back(*entry);
  for (const auto& entry : extra) {
    const std::string key = env_key(entry);
    env.erase(std::remove_if(env.begin(), env.end(),
                             [&](const std::string& existing) { return env_key(existing) == key; }),
              env.end());
    env.push_back(entry);
  }
  return env;
}

void close_all(std::initializer_list<int> fds) {
  for (const int fd : fds) {
    if (fd >= 0) close(fd);
  }
}

// Opens `path` onto `target` (stdin, stderr).
bool open_onto(int target, const char* path, int flags) {
  const int fd = open(path, flags, 0644);
  if (fd < 0) return false;
  if (fd == target) return true;
  const bool ok = dup2(fd, target) >= 0;
  close(fd);
  return ok;
}

// Every descriptor above stderr but `keep`.
void close_others(int keep) {
  if (keep > STDERR_FILENO + 1) close_range(STDERR_FILENO + 1, keep - 1, 0);
  close_range(keep + 1, ~0U, 0);
}

// The child's end when it cannot become the process asked for: errno to the parent.
[[noreturn]] void report_and_exit(int error_fd) noexcept {
  const int error = errno;
  const ssize_t written = write(error_fd, &error, sizeof error);
  (void)written;
  _exit(127);
}

// In the forked child: sets it up as `setup` says and execs; on any failure reports errno
// on setup.error_fd and exits 127.
[[noreturn]] void become_child(const ChildSetup& setup) noexcept {
  const SpawnOptions& options = *setup.options;
  const auto fail = [&] { report_and_exit(setup.error_fd); };
  // Killed when the parent dies, even by SIGKILL: a test or launcher that aborts leaves no
  // process running. A parent that died before the prctl is seen in getppid().
  if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0) fail();
  if (getppid() != setup.parent) _exit(127);
  if (options.new_session) {
    if (setsid() < 0) fail();
  } else if (options.new_process_group && setpgid(0, 0) != 0) {
    fail();
  }
  if (options.ignore_hangup && signal(SIGHUP, SIG_IGN) == SIG_ERR) fail();
  // The child must not inherit blocked SIGINT/SIGTERM from a ShutdownSignal parent.
  sigset_t empty;
  sigemptyset(&empty);
  sigprocmask(SIG_SETMASK, &empty, nullptr);
  if (setup.stdout_fd >= 0 && dup2(setup.stdout_fd, STDOUT_FILENO) < 0) fail();
  if (options.null_stdin && !open_onto(STDIN_FILENO, "/dev/null", O_RDONLY)) fail();
  if (!options.log_file.empty()) {
    const int mode = options.append_log ? O_APPEND : O_TRUNC;
    if (!open_onto(STDERR_FILENO, options.log_file.c_str(), O_WRONLY | O_CREAT | mode)) fail();
    if (!options.capture_stdout && dup2(STDERR_FILENO, STDOUT_FILENO) < 0) fail();
  }
  if (options.close_other_fds) close_others(setup.error_fd);
  if (options.realtime_priority > 0) {
    // Before exec, so that every thread the program starts inherits it. A refusal is not
    // fatal: the parent sees the policy and says so.
    sched_param param{};
    param.sched_priority = options.realtime_priority;
    sched_setscheduler(0, SCHED_FIFO, &param);
  }
  if (!options.cpu_affinity.empty()) {
    // Likewise before exec, and not fatal: a CPU this machine lacks leaves the set empty
    // or smaller, and the parent reads what the child got.
    cpu_set_t set;
    CPU_ZERO(&set);
    for (const int cpu : options.cpu_affinity) {
      if (cpu >= 0 && cpu < CPU_SETSIZE) CPU_SET(cpu, &set);
    }
    sched_setaffinity(0, sizeof set, &set);
  }
  execve(setup.args[0], setup.args.data(), setup.env.data());
  report_and_exit(setup.error_fd);
}

// Blocks until the child has exec'd (EOF: 0) or reported why it could not (its errno).
int child_exec_error(int error_fd) {
  int error = 0;
  ssize_t n;
  do {
    n = read(error_fd, &error, sizeof error);
  } while (n < 0 && errno == EINTR);
  return n == static_cast<ssize_t>(sizeof error) ? error : 0;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv,
                           const std::vector<std::string>& extra_env, bool capture_stdout)
    : ChildProcess(argv, [&] {
        SpawnOptions options;
        options.extra_env = extra_env;
        options.capture_stdout = capture_stdout;
        return options;
      }()) {}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const SpawnOptions& options) {
  if (argv.empty()) throw std::runtime_error("cannot start a process without an argv");
  ChildSetup setup;
  setup.options = &options;
  for (const auto& arg : argv) setup.args.push_back(const_cast<char*>(arg.c_str()));
  setup.args.push_back(nullptr);
  std::vector<std::string> env_storage = child_environment(options.extra_env);
  for (auto& entry : env_storage) setup.env.push_back(entry.data());
  setup.env.push_back(nullptr);

  int stdout_fds[2] = {-1, -1};
  // Close-on-exec, so later children do not hold the write end open (dup2 clears the flag).
  if (options.capture_stdout && pipe2(stdout_fds, O_CLOEXEC) != 0) {
    throw std::runtime_error("pipe() failed");
  }
  int error_fds[2] = {-1, -1};  // the child's errno if it cannot exec; EOF once it has
  if (pipe2(error_fds, O_CLOEXEC) != 0) {
    close_all({stdout_fds[0], stdout_fds[1]});
    throw std::runtime_error("pipe() failed");
  }
  setup.stdout_fd = stdout_fds[1];
  setup.error_fd = error_fds[1];
  setup.parent = getpid();
  pid_ = fork();
  if (pid_ == 0) become_child(setup);
  const int fork_error = errno;
  close_all({stdout_fds[1], error_fds[1]});
  stdout_fd_ = stdout_fds[0];
  const int error = pid_ < 0 ? fork_error : child_exec_error(error_fds[0]);
  close(error_fds[0]);
  if (error != 0) {
    if (pid_ > 0) waitpid(pid_, nullptr, 0);
    pid_ = -1;
    close_all({stdout_fd_});
    stdout_fd_ = -1;
    throw std::runtime_error("cannot start " + argv.front() + ": " + std::strerror(error));
  }
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !exit_code_) terminate(std::chrono::milliseconds(2000));
  if (stdout_fd_ >= 0) close(stdout_fd_);
}

std::optional<std::string> ChildProcess::read_line(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (const auto newline = buffer_.find('\n'); newline != std::string::npos) {
      std::string line = buffer_.substr(0, newline);
      buffer_.erase(0, newline + 1);
      return line;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (stdout_fd_ < 0 || left.count() <= 0) return std::nullopt;
    pollfd fd{stdout_fd_, POLLIN, 0};
    if (poll(&fd, 1, static_cast<int>(left.count())) <= 0) return std::nullopt;
    char chunk[4096];
    const ssize_t n = read(stdout_fd_, chunk, sizeof(chunk));
    if (n <= 0) return std::nullopt;
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

bool ChildProcess::realtime() const {
  return sched_getscheduler(pid_) == SCHED_FIFO;
}

std::vector<int> ChildProcess::cpus() const {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(pid_, sizeof set, &set) != 0) return {};
  return cpus_of(set);
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
  if (exit_code_) return exit_code_;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    int status = 0;
    rusage usage{};
    const pid_t done = wait4(pid_, &status, WNOHANG, &usage);
    if (done == pid_) {
      cpu_s_ = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
               1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
      max_rss_kib_ = static_cast<std::int64_t>(usage.ru_maxrss);
      killed_by_signal_ = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return exit_code_;
    }
    if (done < 0 || std::chrono::steady_clock::now() >= deadline) {
      return done < 0 ? std::optional<int>(-1) : std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

int ChildProcess::terminate(std::chrono::milliseconds timeout, int signal_number) {
  if (exit_code_) return *exit_code_;
  kill(pid_, signal_number);
  if (auto code = wait(timeout)) return *code;
  kill(pid_, SIGKILL);
  return wait(std::chrono::milliseconds(5000)).value_or(-1);
}

}  // namespace cover::process

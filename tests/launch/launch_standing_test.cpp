// Standing and field launches with real processes (fake_process): a terminal hang-up stops
// nothing, a dying process is respawned while the others keep their pids, one that dies
// for good is logged while the others go on, and keep_running processes outlive the run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cover/test/process_alive.hpp"
#include "launch_test_support.hpp"

namespace {

using namespace cover::launch::testing;
using cover::test::process_alive;

// Three services of a standing system: each waits for SIGINT; none ends the run.
constexpr const char* kStanding = R"(
launch:
  name: standing
  kind: standing
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, args: ["--ready={run_dir}/sim.ready"]}
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"],
       respawn_delay_s: 0.05}
    - {name: uav0, executable: fake_process, args: ["--ready={run_dir}/uav0.ready"]}
)";

class LaunchStanding : public LaunchProcess {
 protected:
  bool all_ready(std::initializer_list<const char*> names) const {
    for (const char* name : names) {
      if (!fs::exists(run_dir_ / (std::string(name) + ".ready"))) return false;
    }
    return true;
  }
  // After a respawn the ready file is there from the first run: wait on the log instead.
  bool log_says(const std::string& text) const { return contains(launch_log(), text); }
};

TEST_F(LaunchStanding, SighupToTheLauncherAndItsGroupStopsNothing) {
  auto launcher = start({write_launch(kStanding), "--run-dir", run_dir_.string(), "--json"},
                        /*own_group=*/true);
  ASSERT_TRUE(eventually([&] { return all_ready({"sim", "ugv0", "uav0"}); })) << launch_log();
  std::vector<int> pids;
  for (const char* name : {"sim", "ugv0", "uav0"}) {
    pids.push_back(pid_of(name));
    // A session of its own (no terminal can hang it up), SIGHUP ignored besides.
    EXPECT_TRUE(contains(log_of(name), "session leader: yes")) << log_of(name);
    EXPECT_TRUE(contains(log_of(name), "sighup: ignored")) << log_of(name);
  }
  kill(launcher->pid(), SIGHUP);
  ASSERT_TRUE(eventually([&] { return log_says("SIGHUP received (1)"); })) << launch_log();
  killpg(launcher->pid(), SIGHUP);  // what a shell sends its jobs when it is hung up
  ASSERT_TRUE(eventually([&] { return log_says("SIGHUP received (2)"); })) << launch_log();
  // A hang-up reaching each child's own group changes nothing either.
  for (const int pid : pids) killpg(pid, SIGHUP);
  EXPECT_TRUE(process_alive(launcher->pid()));
  for (const int pid : pids) EXPECT_TRUE(process_alive(pid)) << pid;
  EXPECT_FALSE(log_says("died")) << launch_log();

  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 130) << result.err;
  const auto report = result.json();
  for (const auto& process : report.at("processes")) {
    EXPECT_EQ(process.at("stopped_by"), "SIGINT") << process.dump();
    EXPECT_EQ(process.at("exit_code"), 0) << process.dump();
    EXPECT_EQ(process.at("respawns"), 0) << process.dump();
  }
  for (std::size_t i = 0; i < pids.size(); ++i) {
    EXPECT_EQ(report["processes"][i]["pid"], pids[i]) << "never restarted";
  }
  expect_all_gone(report);
}

// The launcher on a terminal of its own (a pty, as an SSH session gives it), whose master
// side is then closed: the kernel hangs the terminal up and sends SIGHUP to its session.
class PtyLauncher {
 public:
  PtyLauncher(std::vector<std::string> args, const std::string& stderr_path) {
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0) {
      throw std::runtime_error("no pty");
    }
    const std::string slave = ptsname(master_);
    args.insert(args.begin(), COVER_LAUNCH);
    std::vector<char*> argv;
    for (auto& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ == 0) {
      // Only async-signal-safe calls: the test may have threads.
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(127);
      setsid();
      const int tty = open(slave.c_str(), O_RDWR);  // a session leader's first tty: its terminal
      const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (tty < 0 || err < 0) _exit(127);
      dup2(tty, STDIN_FILENO);
      dup2(tty, STDOUT_FILENO);
      dup2(err, STDERR_FILENO);
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  ~PtyLauncher() {
    if (pid_ > 0 && !status_) {
      kill(pid_, SIGKILL);
      wait_exit(std::chrono::milliseconds(5000));
    }
    if (master_ >= 0) close(master_);
  }
  pid_t pid() const { return pid_; }
  void hang_up() {
    close(master_);
    master_ = -1;
  }
  // The exit status once the launcher has ended, nullopt on timeout (scaled).
  std::optional<int> wait_exit(std::chrono::milliseconds timeout) {
    cover::test::wait_until(
        [&] {
          int status = 0;
          if (!status_ && waitpid(pid_, &status, WNOHANG) == pid_) {
            status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
          }
          return status_.has_value();
        },
        timeout);
    return status_;
  }

 private:
  int master_ = -1;
  pid_t pid_ = -1;
  std::optional<int> status_;
};

TEST_F(LaunchStanding, ClosingTheLaunchersTerminalStopsNothing) {
  PtyLauncher launcher({write_launch(kStanding), "--run-dir", run_dir_.string()},
                       (dir_ / "launcher.stderr").string());
  ASSERT_TRUE(eventually([&] { return all_ready({"sim", "ugv0", "uav0"}); })) << launch_log();
  std::vector<int> pids;
  for (const char* name : {"sim", "ugv0", "uav0"}) pids.push_back(pid_of(name));
  launcher.hang_up();
  ASSERT_TRUE(eventually([&] { return log_says("SIGHUP received (1)"); })) << launch_log();
  EXPECT_FALSE(launcher.wait_exit(milliseconds(0))) << "the launcher died of the hang-up";
  for (const int pid : pids) EXPECT_TRUE(process_alive(pid)) << pid;

  kill(launcher.pid(), SIGINT);
  EXPECT_EQ(launcher.wait_exit(milliseconds(8000)), std::optional<int>(130)) << launch_log();
  for (const int pid : pids) EXPECT_TRUE(eventually([&] { return pid_gone(pid); })) << pid;
  for (const char* name : {"sim", "ugv0", "uav0"}) {
    EXPECT_TRUE(contains(log_of(name), "got SIGINT")) << log_of(name);
  }
}

TEST_F(LaunchStanding, AKilledProcessIsRespawnedAndTheOthersKeepTheirPids) {
  auto launcher = start({write_launch(kStanding), "--run-dir", run_dir_.string(), "--json"});
  ASSERT_TRUE(eventually([&] { return all_ready({"sim", "ugv0", "uav0"}); })) << launch_log();
  const int sim = pid_of("sim");
  const int ugv0 = pid_of("ugv0");
  const int uav0 = pid_of("uav0");
  kill(ugv0, SIGKILL);
  ASSERT_TRUE(eventually([&] { return started_pids(launch_log(), "ugv0").size() == 2; }))
      << launch_log();
  const int respawned = started_pids(launch_log(), "ugv0")[1];
  EXPECT_NE(respawned, ugv0);
  EXPECT_TRUE(log_says("ugv0 (pid " + std::to_string(ugv0) + ") died: killed by signal 9"))
      << launch_log();
  EXPECT_TRUE(log_says("started ugv0 pid " + std::to_string(respawned) + " (respawn 1)"));
  EXPECT_TRUE(eventually([&] { return pid_of("ugv0") == respawned; })) << log_of("ugv0");
  EXPECT_TRUE(process_alive(sim));
  EXPECT_TRUE(process_alive(uav0));
  EXPECT_EQ(started_pids(launch_log(), "sim"), std::vector<int>{sim});
  EXPECT_EQ(started_pids(launch_log(), "uav0"), std::vector<int>{uav0});

  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 130) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][1]["respawns"], 1);
  EXPECT_EQ(report["processes"][1]["pid"], respawned);
  EXPECT_EQ(report["processes"][0]["pid"], sim);
  EXPECT_EQ(report["processes"][2]["pid"], uav0);
  expect_all_gone(report);
}

TEST_F(LaunchStanding, AProcessThatDiesForGoodIsLoggedAndTheOthersGoOn) {
  auto launcher = start({write_launch(R"(
launch:
  name: standing-final
  kind: standing
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, args: ["--ready={run_dir}/sim.ready"]}
    - {name: once, executable: fake_process, args: [--mode=exit, --code=5], respawn: false}
    - name: crashing
      executable: fake_process
      args: [--mode=signal]
      respawn_delay_s: 0
      max_respawns: 2
)"),
                         "--run-dir", run_dir_.string(), "--json"});
  ASSERT_TRUE(eventually([&] {
    return fs::exists(run_dir_ / "sim.ready") && log_says("not restarted (respawn: false)") &&
           log_says("not restarted (max_respawns 2 used up)");
  })) << launch_log();
  EXPECT_TRUE(log_says("once (pid ")) << launch_log();
  EXPECT_TRUE(
      log_says("died: exit code 5; not restarted (respawn: false); the other processes "
               "go on"))
      << launch_log();
  EXPECT_TRUE(process_alive(pid_of("sim")));
  EXPECT_TRUE(process_alive(launcher->pid()));
  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 130) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][0]["stopped_by"], "SIGINT");
  EXPECT_EQ(report["processes"][1]["exit_code"], 5);
  EXPECT_EQ(report["processes"][2]["respawns"], 2);
  expect_all_gone(report);
}

TEST_F(LaunchStanding, WhenEveryProcessHasEndedTheLauncherExits4) {
  const auto result = run(R"(
launch:
  name: standing-empty
  kind: standing
  grace_period_s: 0.3
  processes:
    - {name: a, executable: fake_process, args: [--mode=exit, --code=0], respawn: false}
    - {name: b, executable: fake_process, args: [--mode=exit, --code=1], respawn: false}
)",
                          {"--json"});
  EXPECT_EQ(result.exit_code, 4) << result.err;
  EXPECT_TRUE(contains(result.err, "every process has ended")) << result.err;
}

// A field vehicle: the bridge outlives the run's end by another process's exit, and stops
// only with a signal to the launcher.
TEST_F(LaunchStanding, KeepRunningOutlivesTheRunsEndUntilASignal) {
  auto launcher = start({write_launch(R"(
launch:
  name: field
  kind: field
  grace_period_s: 0.3
  processes:
    - {name: bridge, executable: fake_process, args: ["--ready={run_dir}/bridge.ready"],
       keep_running: true}
    - name: agent
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/bridge.ready", "--await={run_dir}/other.ready"]
      ends_run: true
    - {name: other, executable: fake_process, args: ["--ready={run_dir}/other.ready"]}
)"),
                         "--run-dir", run_dir_.string(), "--json"});
  ASSERT_TRUE(eventually([&] { return log_says("keep running (keep_running: true)"); }))
      << launch_log();
  const int bridge = pid_of("bridge");
  EXPECT_TRUE(process_alive(bridge));
  EXPECT_TRUE(eventually([&] { return contains(log_of("other"), "got SIGINT"); }));
  EXPECT_FALSE(contains(log_of("bridge"), "got SIGINT"));
  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 0) << "the run itself completed: " << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][0]["stopped_by"], "SIGINT");
  EXPECT_EQ(report["processes"][0]["pid"], bridge);
  EXPECT_EQ(report["processes"][1]["exit_code"], 0);
  EXPECT_EQ(report["processes"][2]["stopped_by"], "SIGINT");
  EXPECT_TRUE(contains(log_of("bridge"), "got SIGINT"));
  expect_all_gone(report);
}

// A mission keeps today's rule: a process that dies ends the run (exit 4), respawn off.
TEST_F(LaunchStanding, AMissionStillEndsWhenAProcessDies) {
  const auto result = run(R"(
launch:
  name: mission
  kind: mission
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, ends_run: true}
    - {name: ugv0, executable: fake_process, args: [--mode=exit, --code=2]}
)",
                          {"--json"});
  EXPECT_EQ(result.exit_code, 4) << result.err;
  EXPECT_EQ(result.json()["processes"][1]["respawns"], 0);
}

}  // namespace

// cover-launch with real processes: fake_process stands in for the simulator and agents.
// Synchronisation is on conditions with deadlines (ready files, process exits), never on
// sleeps; fake_process's own --after-ms is not used.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <thread>

#include "cover/test/process_alive.hpp"
#include "launch_test_support.hpp"

namespace {

using namespace cover::launch::testing;

TEST_F(LaunchProcess, EndsRunExitZeroStopsOthersInReverseOrder) {
  const auto result = run(R"(
launch:
  name: happy
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/ugv0.ready", "--await={run_dir}/ugv1.ready",
             "--result={run_dir}/result.json"]
      ends_run: true
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"]}
    - {name: ugv1, executable: fake_process, args: ["--ready={run_dir}/ugv1.ready"]}
)",
                          {"--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report.at("exit_code"), 0);
  EXPECT_EQ(report.at("fake"), true);  // result.json of the ends_run process
  EXPECT_EQ(report.at("score"), 7);
  EXPECT_FALSE(report.contains("result_missing"));
  EXPECT_EQ(report.at("run_dir"), run_dir_.string());
  ASSERT_EQ(report.at("processes").size(), 3u);
  for (const auto& process : report.at("processes")) {
    EXPECT_EQ(process.at("exit_code"), 0) << process.dump();
    EXPECT_TRUE(process.at("pid").is_number()) << process.dump();
  }
  EXPECT_EQ(report["processes"][0]["stopped_by"], "");
  EXPECT_EQ(report["processes"][1]["stopped_by"], "SIGINT");
  EXPECT_EQ(report["processes"][2]["stopped_by"], "SIGINT");
  expect_all_gone(report);
  EXPECT_TRUE(contains(log_of("ugv0"), "got SIGINT"));
  EXPECT_TRUE(contains(log_of("ugv1"), "got SIGINT"));
  EXPECT_TRUE(contains(log_of("sim"), "exiting with 0"));
  // Children hold no descriptor of the launcher (launch.log) or of this test (its pipe).
  EXPECT_FALSE(contains(log_of("ugv0"), "open fd")) << log_of("ugv0");

  const std::string launch_log = read_text(run_dir_ / "launch.log");
  const auto stop_ugv1 = launch_log.find("stopping ugv1");
  const auto stop_ugv0 = launch_log.find("stopping ugv0");
  ASSERT_NE(stop_ugv1, std::string::npos) << launch_log;
  ASSERT_NE(stop_ugv0, std::string::npos) << launch_log;
  EXPECT_LT(stop_ugv1, stop_ugv0) << "stop order must be the reverse of the start order";
  EXPECT_TRUE(contains(launch_log, "started sim pid")) << launch_log;
  EXPECT_TRUE(contains(launch_log, "run over")) << launch_log;
}

TEST_F(LaunchProcess, DdsGlobsDomainAndArgumentsReachChildren) {
  const auto result = run(R"(
launch:
  name: env-check
  grace_period_s: 0.3
  variables: {clock: lockstep, seed: "", tag: ""}
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/ugv0.ready", "--await={run_dir}/uav0.ready",
             "--seed={seed}", "--clock={clock}", "--run-id={run_id}", "--domain={domain}"]
      env: {EXTRA: one}
      ends_run: true
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"], dds: cyclone}
    - {name: uav0, executable: fake_process, args: ["--ready={run_dir}/uav0.ready", "--tag={tag}"]}
)",
                          {"--json", "--dds", "*=cyclone", "--dds", "ugv*=fastdds", "--domain",
                           "17", "--seed", "42", "--clock", "realtime"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][0]["dds"], "cyclone");
  EXPECT_EQ(report["processes"][1]["dds"], "fastdds");
  EXPECT_EQ(report["processes"][2]["dds"], "cyclone");
  EXPECT_TRUE(report.at("result_missing").get<bool>());

  const std::string sim = log_of("sim");
  const std::string ugv0 = log_of("ugv0");
  const std::string uav0 = log_of("uav0");
  EXPECT_TRUE(contains(sim, "COVER_DDS=cyclone\n")) << sim;
  EXPECT_TRUE(contains(ugv0, "COVER_DDS=fastdds\n")) << ugv0;
  EXPECT_TRUE(contains(uav0, "COVER_DDS=cyclone\n")) << uav0;
  for (const auto* log : {&sim, &ugv0, &uav0}) {
    EXPECT_TRUE(contains(*log, "COVER_DDS_DOMAIN=17\n")) << *log;
  }
  EXPECT_TRUE(contains(sim, "arg: --seed=42\n")) << sim;
  EXPECT_TRUE(contains(sim, "arg: --clock=realtime\n")) << sim;
  EXPECT_TRUE(contains(sim, "arg: --domain=17\n")) << sim;
  const std::string run_id = report.at("run_id");
  EXPECT_EQ(run_id.rfind("env_check_", 0), 0u) << run_id;
  EXPECT_TRUE(contains(sim, "arg: --run-id=" + run_id + "\n")) << sim;
  EXPECT_FALSE(contains(uav0, "--tag")) << "an argument with an empty placeholder is dropped";
  expect_all_gone(report);
}

// The README lets users export COVER_DDS and COVER_DDS_DOMAIN: a launch still gives each
// process the vendor and domain of its file and flags, and reports what they run (issue
// 31: ugv0 reported on Cyclone DDS ran Fast DDS, the bench's domain lost to an export).
TEST_F(LaunchProcess, ExportedDdsAndDomainGiveWayToTheLaunch) {
  const auto result = run(R"(
launch:
  name: exported
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/ugv0.ready", "--await={run_dir}/ugv1.ready"]
      ends_run: true
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"]}
    - {name: ugv1, executable: fake_process, args: ["--ready={run_dir}/ugv1.ready"]}
)",
                          {"--json", "--dds", "ugv*=cyclone", "--domain", "17"},
                          {"COVER_DDS=fastdds", "COVER_DDS_DOMAIN=150"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  for (const auto& process : report.at("processes")) {
    const std::string name = process.at("name");
    const std::string log = log_of(name);
    EXPECT_TRUE(contains(log, "COVER_DDS=" + process.at("dds").get<std::string>() + "\n"))
        << name << " runs another vendor than its report's:\n"
        << log;
    EXPECT_TRUE(contains(log, "COVER_DDS_DOMAIN=17\n")) << name << ":\n" << log;
  }
  EXPECT_EQ(report["processes"][1]["dds"], "cyclone");
  EXPECT_EQ(report["processes"][2]["dds"], "cyclone");
  expect_all_gone(report);
}

// {state_dir} (a task database's home, issue 31) is made before anything starts, and the
// report names every variable's value as the processes got it.
TEST_F(LaunchProcess, StateDirIsMadeAndTheReportNamesEveryVariable) {
  const fs::path state = dir_ / "state";
  const auto result = run(R"(
launch:
  name: stateful
  kind: standing
  grace_period_s: 0.3
  variables: {db: "{state_dir}/tasks.db", clock: lockstep}
  processes:
    - {name: tm, executable: fake_process, args: [--mode=exit, "--db={db}"], ends_run: true}
)",
                          {"--json"}, {"XDG_STATE_HOME=" + state.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string db = (state / "cover" / "tasks.db").string();
  EXPECT_TRUE(fs::is_directory(state / "cover"));
  const auto report = result.json();
  EXPECT_EQ(report["variables"]["db"], db) << report.dump();
  EXPECT_EQ(report["variables"]["clock"], "lockstep") << report.dump();
  EXPECT_TRUE(contains(log_of("tm"), "arg: --db=" + db + "\n")) << log_of("tm");
  EXPECT_TRUE(contains(launch_log(), "variables: clock=lockstep db=" + db)) << launch_log();
}

// A tool beside the launch (cover-bench mocap) finds the run by what the launch says: its
// identity is in <run_dir>/run.json while the processes run (the ends_run process waits
// for it), and names the run id its processes were given.
TEST_F(LaunchProcess, RunJsonNamesTheRunWhileItsProcessesRun) {
  const auto result = run(R"(
launch:
  name: identity
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/run.json", "--run-id={run_id}"]
      ends_run: true
)",
                          {"--json", "--domain", "23"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  const auto identity = nlohmann::json::parse(read_text(run_dir_ / "run.json"), nullptr, false);
  ASSERT_TRUE(identity.is_object()) << read_text(run_dir_ / "run.json");
  EXPECT_EQ(identity.at("run_id"), report.at("run_id"));
  EXPECT_TRUE(contains(log_of("sim"), "arg: --run-id=" + identity.at("run_id").get<std::string>()));
  EXPECT_EQ(identity.at("name"), "identity");
  EXPECT_EQ(identity.at("kind"), "mission");
  EXPECT_EQ(identity.at("domain"), 23);
  EXPECT_EQ(identity.at("run_dir"), run_dir_.string());
  EXPECT_TRUE(identity.at("launcher_pid").is_number_integer());
  EXPECT_FALSE(std::filesystem::exists(run_dir_ / "run.json.partial"));
}

TEST_F(LaunchProcess, EarlyDeathStopsTheRestAndExits4) {
  const auto result = run(R"(
launch:
  name: death
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, ends_run: true}
    - {name: ugv0, executable: fake_process, args: [--mode=exit, --code=5]}
    - {name: ugv1, executable: fake_process}
)",
                          {"--json"});
  EXPECT_EQ(result.exit_code, 4) << result.err;
  EXPECT_TRUE(contains(result.err, "ugv0 (pid ")) << result.err;
  EXPECT_TRUE(contains(result.err, "died unexpectedly: exit code 5")) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report.at("exit_code"), 4);
  EXPECT_EQ(report["processes"][1]["exit_code"], 5);
  EXPECT_EQ(report["processes"][0]["stopped_by"], "SIGINT");
  EXPECT_EQ(report["processes"][2]["stopped_by"], "SIGINT");
  expect_all_gone(report);
}

TEST_F(LaunchProcess, DeathBySignalIsNamed) {
  const auto result = run(R"(
launch:
  name: crash
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, ends_run: true}
    - {name: uav0, executable: fake_process, args: [--mode=signal]}
)");
  EXPECT_EQ(result.exit_code, 4) << result.err;
  EXPECT_TRUE(contains(result.err, "uav0 (pid ")) << result.err;
  EXPECT_TRUE(
      contains(result.err, "died unexpectedly: killed by signal " + std::to_string(SIGUSR1)))
      << result.err;
}

TEST_F(LaunchProcess, EndsRunFailureExits3) {
  const auto result = run(R"(
launch:
  name: failing
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, --code=7, "--await={run_dir}/ugv0.ready"]
      ends_run: true
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"]}
)");
  EXPECT_EQ(result.exit_code, 3) << result.err;
  EXPECT_TRUE(contains(result.err, "sim failed: exit code 7")) << result.err;
  EXPECT_TRUE(contains(result.out, "exit code 3")) << result.out;  // the readable summary
  EXPECT_TRUE(contains(log_of("ugv0"), "got SIGINT"));
}

TEST_F(LaunchProcess, SigintStopsChildrenAndExits130) {
  const std::string file = write_launch(R"(
launch:
  name: interrupted
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, args: ["--ready={run_dir}/sim.ready"], ends_run: true}
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"]}
)");
  auto launcher = start({file, "--run-dir", run_dir_.string(), "--json"});
  ASSERT_TRUE(eventually([&] {
    return fs::exists(run_dir_ / "sim.ready") && fs::exists(run_dir_ / "ugv0.ready");
  })) << "the children never became ready";
  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 130) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report.at("exit_code"), 130);
  for (const auto& process : report.at("processes")) {
    EXPECT_EQ(process.at("stopped_by"), "SIGINT") << process.dump();
    EXPECT_EQ(process.at("exit_code"), 0) << process.dump();
  }
  expect_all_gone(report);
  EXPECT_TRUE(contains(log_of("sim"), "got SIGINT"));
  EXPECT_TRUE(contains(read_text(run_dir_ / "launch.log"), "interrupted"));
}

// A launcher killed outright (SIGKILL: no handler, no ordered stop) takes its processes
// with it: each dies with its parent (cover::process::ChildProcess).
TEST_F(LaunchProcess, AKilledLauncherLeavesNoProcessRunning) {
  const std::string file = write_launch(R"(
launch:
  name: killed
  processes:
    - {name: sim, executable: fake_process, args: ["--ready={run_dir}/sim.ready"], ends_run: true}
    - {name: ugv0, executable: fake_process, args: ["--ready={run_dir}/ugv0.ready"]}
)");
  auto launcher = start({file, "--run-dir", run_dir_.string()});
  ASSERT_TRUE(eventually([&] {
    return fs::exists(run_dir_ / "sim.ready") && fs::exists(run_dir_ / "ugv0.ready");
  })) << "the children never became ready";
  std::vector<pid_t> pids;
  for (const char* name : {"sim", "ugv0"}) {
    const std::string log = log_of(name);  // "pid: N" first, flushed before the ready file
    const auto at = log.find("pid: ");
    ASSERT_NE(at, std::string::npos) << log;
    pids.push_back(std::stoi(log.substr(at + 5)));
    EXPECT_TRUE(cover::test::process_alive(pids.back())) << name;
  }
  kill(launcher->pid(), SIGKILL);
  EXPECT_EQ(launcher->wait(milliseconds(5000)), std::optional<int>(128 + SIGKILL));
  for (const pid_t pid : pids) {
    const bool ended = eventually([&] { return !cover::test::process_alive(pid); });
    if (!ended) kill(pid, SIGKILL);  // not left running by a failure either
    EXPECT_TRUE(ended) << "pid " << pid << " outlived its launcher";
  }
}

TEST_F(LaunchProcess, EscalatesToSigkillWithinTwoGracePeriods) {
  const auto started = steady_clock::now();
  const auto result = run(R"(
launch:
  name: stubborn
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/stubborn.ready"]
      ends_run: true
    - {name: stubborn, executable: fake_process, args: [--mode=ignore, "--ready={run_dir}/stubborn.ready"]}
)",
                          {"--json"});
  const double elapsed_s = std::chrono::duration<double>(steady_clock::now() - started).count();
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][1]["stopped_by"], "SIGKILL");
  EXPECT_EQ(report["processes"][1]["exit_code"], 128 + SIGKILL);
  expect_all_gone(report);
  const std::string launch_log = read_text(run_dir_ / "launch.log");
  EXPECT_TRUE(contains(launch_log, "stopping stubborn")) << launch_log;
  EXPECT_TRUE(contains(launch_log, "SIGTERM")) << launch_log;
  EXPECT_TRUE(contains(launch_log, "SIGKILL")) << launch_log;
  // Two grace periods of 0.3 s were waited out, and not much more.
  EXPECT_GE(elapsed_s, 0.6);
  EXPECT_LT(elapsed_s, 3.0);
}

TEST_F(LaunchProcess, LeftoverShmEntryOfTheRunIsRemoved) {
  const auto result = run(R"(
launch:
  name: leaky
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, args: [--mode=exit, "--shm=cover_{run_id}_seg"], ends_run: true}
)",
                          {"--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  const std::string segment = "cover_" + report.at("run_id").get<std::string>() + "_seg";
  EXPECT_EQ(report.at("leftover_segments"), nlohmann::json::array({segment}));
  EXPECT_FALSE(fs::exists(fs::path("/dev/shm") / segment));
  EXPECT_TRUE(contains(read_text(run_dir_ / "launch.log"),
                       "leftover segment removed: /dev/shm/" + segment));
}

TEST_F(LaunchProcess, RespawningProcessIsRestartedAndTheRunEndsNormally) {
  // ugv0's first run exits 3 at once; its restart waits for SIGINT. The simulator ends the
  // run once the restarted ugv0 is ready, which only the second run gets to.
  const auto result = run(R"(
launch:
  name: respawn
  grace_period_s: 0.3
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/ugv0.ready"]
      ends_run: true
    - name: ugv0
      executable: fake_process
      args: ["--once={run_dir}/ugv0.first", --code=3, "--ready={run_dir}/ugv0.ready"]
      respawn: true
      respawn_delay_s: 0.05
)",
                          {"--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][0]["respawns"], 0);
  EXPECT_EQ(report["processes"][1]["respawns"], 1);
  EXPECT_EQ(report["processes"][1]["stopped_by"], "SIGINT");
  EXPECT_EQ(report["processes"][1]["exit_code"], 0);  // the latest run's

  const std::string launch_log = read_text(run_dir_ / "launch.log");
  const auto pids = started_pids(launch_log, "ugv0");
  ASSERT_EQ(pids.size(), 2u) << launch_log;
  EXPECT_NE(pids[0], pids[1]);
  EXPECT_EQ(report["processes"][1]["pid"], pids[1]) << "the latest pid is reported";
  const std::string died = "ugv0 (pid " + std::to_string(pids[0]) +
                           ") died: exit code 3; respawning in 0.05 s (1 of 10)";
  EXPECT_TRUE(contains(launch_log, died)) << launch_log;
  EXPECT_TRUE(contains(launch_log, "started ugv0 pid " + std::to_string(pids[1]) + " (respawn 1)"))
      << launch_log;
  // The log was appended to: both runs' lines, same argv and environment.
  const std::string ugv0 = log_of("ugv0");
  EXPECT_TRUE(contains(ugv0, "pid: " + std::to_string(pids[0]) + "\n")) << ugv0;
  EXPECT_TRUE(contains(ugv0, "first run: exiting with 3")) << ugv0;
  EXPECT_TRUE(contains(ugv0, "pid: " + std::to_string(pids[1]) + "\n")) << ugv0;
  EXPECT_TRUE(contains(ugv0, "got SIGINT")) << ugv0;
  EXPECT_EQ(count(ugv0, "COVER_DDS=fastdds\n"), 2u) << ugv0;
  EXPECT_LT(ugv0.find("first run"), ugv0.find("got SIGINT")) << ugv0;
  expect_all_gone(report);
  EXPECT_TRUE(pid_gone(pids[0]));
}

TEST_F(LaunchProcess, MaxRespawnsExceededExits4NamingIt) {
  // Death by a signal is respawned too; with no delay the limit is reached at once.
  const auto result = run(R"(
launch:
  name: crashloop
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, ends_run: true}
    - name: uav0
      executable: fake_process
      args: [--mode=signal]
      respawn: true
      respawn_delay_s: 0
      max_respawns: 2
)",
                          {"--json"});
  EXPECT_EQ(result.exit_code, 4) << result.err;
  const std::string signal_text = "killed by signal " + std::to_string(SIGUSR1);
  EXPECT_TRUE(contains(result.err, "died: " + signal_text)) << result.err;
  EXPECT_TRUE(contains(result.err, "respawning in 0.0 s (1 of 2)")) << result.err;
  EXPECT_TRUE(contains(result.err, "respawning in 0.0 s (2 of 2)")) << result.err;
  EXPECT_FALSE(contains(result.err, "(3 of 2)")) << result.err;
  EXPECT_TRUE(contains(result.err, "uav0 (pid ")) << result.err;
  EXPECT_TRUE(contains(result.err, "died unexpectedly: " + signal_text)) << result.err;
  EXPECT_TRUE(contains(result.err, "max_respawns 2 used up")) << result.err;
  const auto report = result.json();
  EXPECT_EQ(report["processes"][1]["respawns"], 2);
  EXPECT_EQ(report["processes"][1]["exit_code"], 128 + SIGUSR1);
  EXPECT_EQ(report["processes"][0]["stopped_by"], "SIGINT");
  EXPECT_EQ(count(log_of("uav0"), "pid: "), 3u) << "three runs, one log";
  expect_all_gone(report);
}

TEST_F(LaunchProcess, SigintDuringRespawnDelayDoesNotRestart) {
  const std::string file = write_launch(R"(
launch:
  name: interrupted-respawn
  grace_period_s: 0.3
  processes:
    - {name: sim, executable: fake_process, args: ["--ready={run_dir}/sim.ready"], ends_run: true}
    - name: ugv0
      executable: fake_process
      args: [--mode=exit, --code=1]
      respawn: true
      respawn_delay_s: 30
)");
  const auto started = steady_clock::now();
  auto launcher = start({file, "--run-dir", run_dir_.string(), "--json"});
  const auto launch_log = [&] { return read_text(run_dir_ / "launch.log"); };
  ASSERT_TRUE(eventually([&] {
    return fs::exists(run_dir_ / "sim.ready") && contains(launch_log(), "respawning in 30.0 s");
  })) << "ugv0 never died: "
      << launch_log();
  kill(launcher->pid(), SIGINT);
  const auto result = finish(*launcher);
  const double elapsed_s = std::chrono::duration<double>(steady_clock::now() - started).count();
  EXPECT_EQ(result.exit_code, 130) << result.err;
  EXPECT_LT(elapsed_s, 10.0) << "the respawn delay must not hold up the shutdown";
  const auto report = result.json();
  EXPECT_EQ(report["processes"][1]["respawns"], 0);
  EXPECT_EQ(report["processes"][1]["exit_code"], 1);
  EXPECT_EQ(report["processes"][1]["stopped_by"], "");
  EXPECT_EQ(report["processes"][0]["stopped_by"], "SIGINT");
  EXPECT_EQ(started_pids(launch_log(), "ugv0").size(), 1u) << launch_log();
  EXPECT_TRUE(contains(launch_log(), "ugv0: waiting for its respawn, not restarted"))
      << launch_log();
  EXPECT_EQ(count(log_of("ugv0"), "pid: "), 1u) << log_of("ugv0");
  expect_all_gone(report);
}

TEST_F(LaunchProcess, MissingExecutableStartsNothingAndExits4) {
  const auto result = run(R"(
launch:
  name: typo
  processes:
    - {name: sim, executable: fake_process, ends_run: true}
    - {name: ugv0, executable: no-such-cover-executable}
)",
                          {"--json"});
  EXPECT_EQ(result.exit_code, 4) << result.err;
  EXPECT_TRUE(contains(result.err, "no-such-cover-executable")) << result.err;
  const auto report = result.json();
  EXPECT_TRUE(report["processes"][0]["pid"].is_null()) << "nothing starts when one is missing";
}

TEST_F(LaunchProcess, UsageErrorsExit2) {
  const char* valid = R"(
launch:
  name: ok
  processes: [{name: sim, executable: fake_process, ends_run: true}]
)";
  auto result = run(R"(
launch:
  name: bad
  processes: [{name: sim, executable: fake_process, ends_run: true, arg: []}]
)");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.err, "unknown key 'arg'")) << result.err;
  result = run(R"(
launch:
  name: bad
  processes: [{name: sim, executable: fake_process, ends_run: true, respawn: true}]
)");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.err, "respawn: true and ends_run: true")) << result.err;
  result = run(valid, {"--dds", "uav*=cyclone"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.err, "uav*")) << result.err;
  result = run(valid, {"--domain", "300"});
  EXPECT_EQ(result.exit_code, 2);
  result = run(valid, {"--clock", "warp"});
  EXPECT_EQ(result.exit_code, 2);
  result = run(valid, {"--seed", "1.5"});
  EXPECT_EQ(result.exit_code, 2);
  result = run(valid, {"--seed", "1"});  // the file has no {seed}
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_TRUE(contains(result.err, "'seed'")) << result.err;
}

TEST_F(LaunchProcess, HelpExplainsFormatAndExitCodes) {
  auto launcher = start({"--help"});
  const auto result = finish(*launcher);
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_TRUE(contains(result.out, "ends_run")) << result.out;
  EXPECT_TRUE(contains(result.out, "respawn_delay_s")) << result.out;
  EXPECT_TRUE(contains(result.out, "Exit codes")) << result.out;
  EXPECT_TRUE(contains(result.out, "130")) << result.out;
}

}  // namespace

namespace {

// The run report's entry of process `name`; an empty object if it has none.
nlohmann::json process_report(const nlohmann::json& report, const std::string& name) {
  for (const auto& process : report["processes"]) {
    if (process["name"] == name) return process;
  }
  return nlohmann::json::object();
}

// A process given realtime_priority runs SCHED_FIFO at it, every thread it starts too, when
// the run is realtime and the launcher may (root here); the launcher says which it did.
TEST_F(LaunchProcess, RealtimePriorityIsSchedFifoInRealtimeOnly) {
  const std::string yaml = R"(
launch:
  name: rt-priority
  grace_period_s: 0.3
  variables: {clock: lockstep}
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/uav0.ready"]
      ends_run: true
    - {name: uav0, executable: fake_process, args: ["--ready={run_dir}/uav0.ready"],
       realtime_priority: 12}
)";
  const bool may = geteuid() == 0;
  const auto realtime = run(yaml, {"--json", "--clock", "realtime"});
  ASSERT_EQ(realtime.exit_code, 0) << realtime.err;
  EXPECT_TRUE(contains(log_of("sim"), "thread sched: other 0\n")) << log_of("sim");
  if (may) {
    EXPECT_TRUE(contains(log_of("uav0"), "thread sched: fifo 12\n")) << log_of("uav0");
    EXPECT_TRUE(contains(realtime.err, "uav0 runs SCHED_FIFO priority 12")) << realtime.err;
  } else {
    EXPECT_TRUE(contains(log_of("uav0"), "thread sched: other 0\n")) << log_of("uav0");
    EXPECT_TRUE(contains(realtime.err, "uav0: SCHED_FIFO priority 12 refused")) << realtime.err;
  }
  expect_all_gone(realtime.json());
  // The report says at what priority each process ran: what a latency is compared under.
  const auto priority_in = [](const nlohmann::json& report, const std::string& name) {
    return process_report(report, name).value("realtime_priority", -1);
  };
  EXPECT_EQ(priority_in(realtime.json(), "uav0"), may ? 12 : 0);
  EXPECT_EQ(priority_in(realtime.json(), "sim"), 0);

  fs::remove_all(run_dir_);  // the first run's ready file would let the sim end at once
  const auto lockstep = run(yaml, {"--json"});
  ASSERT_EQ(lockstep.exit_code, 0) << lockstep.err;
  EXPECT_TRUE(contains(log_of("uav0"), "thread sched: other 0\n")) << log_of("uav0");
  EXPECT_TRUE(contains(lockstep.err, "uav0: realtime_priority 12 not applied")) << lockstep.err;
  EXPECT_EQ(priority_in(lockstep.json(), "uav0"), 0);
  expect_all_gone(lockstep.json());
}

// A process given cpu_affinity runs (every thread it starts too) on those CPUs in a
// realtime run, and on any in lockstep; the launcher says which, and the report gives them.
TEST_F(LaunchProcess, CpuAffinityPinsInRealtimeOnly) {
  const std::string yaml = R"(
launch:
  name: cpu-affinity
  grace_period_s: 0.3
  variables: {clock: lockstep}
  processes:
    - name: sim
      executable: fake_process
      args: [--mode=exit, "--await={run_dir}/uav0.ready"]
      ends_run: true
    - {name: uav0, executable: fake_process, args: ["--ready={run_dir}/uav0.ready"],
       cpu_affinity: [0]}
)";
  const auto cpus_in = [](const nlohmann::json& report, const std::string& name) {
    return process_report(report, name).value("cpus", std::vector<int>{-1});
  };
  const auto realtime = run(yaml, {"--json", "--clock", "realtime"});
  ASSERT_EQ(realtime.exit_code, 0) << realtime.err;
  EXPECT_TRUE(contains(log_of("uav0"), "thread cpus: 0\n")) << log_of("uav0");
  EXPECT_TRUE(contains(realtime.err, "uav0 runs on CPU 0")) << realtime.err;
  EXPECT_EQ(cpus_in(realtime.json(), "uav0"), std::vector<int>{0});
  EXPECT_TRUE(cpus_in(realtime.json(), "sim").empty());
  expect_all_gone(realtime.json());

  fs::remove_all(run_dir_);
  const auto lockstep = run(yaml, {"--json"});
  ASSERT_EQ(lockstep.exit_code, 0) << lockstep.err;
  if (std::thread::hardware_concurrency() > 1) {
    EXPECT_FALSE(contains(log_of("uav0"), "thread cpus: 0\n")) << log_of("uav0");
  }
  EXPECT_TRUE(contains(lockstep.err, "uav0: cpu_affinity 0 not applied in lockstep"))
      << lockstep.err;
  EXPECT_TRUE(cpus_in(lockstep.json(), "uav0").empty());
  expect_all_gone(lockstep.json());
}

}  // namespace

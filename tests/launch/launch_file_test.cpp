// Launch-file parsing and validation: every error names what is wrong.
#include <gtest/gtest.h>
#include <algorithm>

#include <string>

#include "cover/config/config_error.hpp"
#include "cover/launch/launch_file.hpp"

namespace cover::launch {
namespace {

LaunchFile parse(const std::string& yaml) {
  return LaunchFile::parse(YAML::Load(yaml), "test.yaml", "/launch/dir");
}

// The message of the ConfigError that parsing `yaml` throws; fails the test otherwise.
std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return "";
}

const char* kValid = R"(
launch:
  name: scenario2
  grace_period_s: 0.5
  variables: {clock: lockstep, seed: ""}
  processes:
    - name: sim
      executable: cover-sim
      args: [--scenario, scenario2, "--clock={clock}", "--seed={seed}", "--result={run_dir}/r.json"]
      dds: fastdds
      env: {COVER_LOG_LEVEL: info}
      ends_run: true
    - name: ugv0
      executable: ./bin/cover-ugv-agent
      args: [--id, "0", "--run-id={run_id}"]
      dds: cyclone
      respawn: true
      respawn_delay_s: 0.25
      max_respawns: 3
)";

TEST(LaunchFile, ParsesEveryKey) {
  const LaunchFile file = parse(kValid);
  EXPECT_EQ(file.name, "scenario2");
  EXPECT_DOUBLE_EQ(file.grace_period_s, 0.5);
  EXPECT_EQ(file.variables.at("clock"), "lockstep");
  EXPECT_EQ(file.variables.at("seed"), "");
  EXPECT_EQ(file.directory, "/launch/dir");
  ASSERT_EQ(file.processes.size(), 2u);
  EXPECT_EQ(file.processes[0].name, "sim");
  EXPECT_EQ(file.processes[0].args.size(), 5u);
  EXPECT_EQ(file.processes[0].env.at("COVER_LOG_LEVEL"), "info");
  EXPECT_TRUE(file.processes[0].ends_run);
  EXPECT_EQ(file.processes[1].executable, "./bin/cover-ugv-agent");
  EXPECT_EQ(file.processes[1].dds, "cyclone");
  EXPECT_FALSE(file.processes[1].ends_run);
  EXPECT_TRUE(file.processes[1].respawn.enabled);
  EXPECT_DOUBLE_EQ(file.processes[1].respawn.delay_s, 0.25);
  EXPECT_EQ(file.processes[1].respawn.max_respawns, 3);
}

TEST(LaunchFile, DefaultsStandForOptionalKeys) {
  const LaunchFile file = parse(R"(
launch:
  name: tiny
  processes:
    - {name: only, executable: x, ends_run: true}
)");
  EXPECT_DOUBLE_EQ(file.grace_period_s, 3.0);
  EXPECT_TRUE(file.variables.empty());
  EXPECT_EQ(file.processes[0].dds, "fastdds");
  EXPECT_TRUE(file.processes[0].args.empty());
  EXPECT_FALSE(file.processes[0].respawn.enabled);
  EXPECT_DOUBLE_EQ(file.processes[0].respawn.delay_s, 1.0);
  EXPECT_EQ(file.processes[0].respawn.max_respawns, 10);
}

TEST(LaunchFile, RespawnKeysAreValidated) {
  const auto error_with = [](const std::string& keys) {
    return error_of(
        "launch: {name: a, processes: [{name: p, executable: x, ends_run: true}, "
        "{name: q, executable: y, " +
        keys + "}]}");
  };
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  const std::string both = error_of(
      "launch: {name: a, processes: [{name: p, executable: x, ends_run: true, "
      "respawn: true}]}");
  EXPECT_TRUE(contains(both, "respawn: true and ends_run: true")) << both;
  EXPECT_TRUE(contains(both, "process 'p'")) << both;
  const std::string negative = error_with("respawn: true, respawn_delay_s: -0.5");
  EXPECT_TRUE(contains(negative, "respawn_delay_s must be")) << negative;
  EXPECT_TRUE(contains(negative, "process 'q'")) << negative;
  EXPECT_TRUE(contains(error_with("respawn: true, respawn_delay_s: .nan"), "respawn_delay_s"));
  EXPECT_TRUE(contains(error_with("respawn: true, max_respawns: 0"), "max_respawns must be >= 1"));
  EXPECT_TRUE(contains(error_with("respawn: true, max_respawns: 1.5"), "max_respawns"));
  EXPECT_TRUE(contains(error_with("respawn: yes please"), "respawn"));
  EXPECT_TRUE(contains(error_with("respawns: true"), "unknown key 'respawns'"));
  // A delay of 0 restarts at once; max_respawns bounds it.
  EXPECT_NO_THROW(
      parse("launch: {name: a, processes: [{name: p, executable: x, ends_run: true}, "
            "{name: q, executable: y, respawn: true, respawn_delay_s: 0, "
            "max_respawns: 1}]}"));
}

TEST(LaunchFile, UnknownKeysAreNamed) {
  EXPECT_NE(error_of(R"(
launch:
  name: a
  grace_period: 1
  processes: [{name: p, executable: x, ends_run: true}]
)")
                .find("unknown key 'grace_period'"),
            std::string::npos);
  const std::string in_process = error_of(R"(
launch:
  name: a
  processes: [{name: p, executable: x, ends_run: true, argz: []}]
)");
  EXPECT_NE(in_process.find("unknown key 'argz'"), std::string::npos) << in_process;
  EXPECT_NE(in_process.find("(p)"), std::string::npos) << in_process;
  EXPECT_NE(error_of("launch: {name: a, processes: []}\nextra: 1\n").find("unknown key 'extra'"),
            std::string::npos);
}

TEST(LaunchFile, MissingKeysAreNamed) {
  EXPECT_NE(error_of("launch: {processes: [{name: p, executable: x, ends_run: true}]}")
                .find("missing required key 'name'"),
            std::string::npos);
  EXPECT_NE(error_of("launch: {name: a, processes: [{name: p, ends_run: true}]}")
                .find("missing required key 'executable'"),
            std::string::npos);
  EXPECT_NE(error_of("other: 1").find("missing section 'launch'"), std::string::npos);
}

TEST(LaunchFile, UnknownPlaceholderNamesProcessAndArgument) {
  const std::string message = error_of(R"(
launch:
  name: a
  variables: {clock: lockstep}
  processes:
    - {name: sim, executable: x, ends_run: true, args: ["--clock={clock}", "--speed={speed}"]}
)");
  EXPECT_NE(message.find("process 'sim'"), std::string::npos) << message;
  EXPECT_NE(message.find("'--speed={speed}'"), std::string::npos) << message;
  EXPECT_NE(message.find("{speed}"), std::string::npos) << message;
}

TEST(LaunchFile, StructuralErrors) {
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  EXPECT_TRUE(contains(error_of(R"(
launch:
  name: a
  processes:
    - {name: ugv, executable: x, ends_run: true}
    - {name: ugv, executable: y}
)"),
                       "duplicate process name 'ugv'"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, processes: []}"), "no process"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, processes: [{name: p, executable: x}]}"),
                       "exactly one process must have ends_run: true (found 0)"));
  EXPECT_TRUE(contains(error_of(R"(
launch:
  name: a
  processes:
    - {name: p, executable: x, ends_run: true}
    - {name: q, executable: x, ends_run: true}
)"),
                       "(found 2)"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, processes: [{name: p, executable: x, ends_run: true, dds: "
               "opendds}]}"),
      "dds: 'opendds'"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, processes: [{name: p, executable: x, ends_run: true, env: "
               "{COVER_DDS: cyclone}}]}"),
      "COVER_DDS is set by the launcher"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, processes: [{name: p, executable: x, ends_run: true, netns: "
               "'a b'}]}"),
      "netns: 'a b'"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, variables: {run_id: x}, processes: [{name: p, executable: x, "
               "ends_run: true}]}"),
      "'run_id' is a built-in placeholder"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, processes: [{name: a/b, executable: x, ends_run: true}]}"),
      "process name 'a/b'"));
  EXPECT_TRUE(contains(
      error_of("launch: {name: a, processes: [{name: launch, executable: x, ends_run: true}]}"),
      "launch.log"));
  EXPECT_TRUE(
      contains(error_of("launch: {name: a, grace_period_s: 0, processes: [{name: p, executable: x, "
                        "ends_run: true}]}"),
               "grace_period_s"));
}

TEST(LaunchFile, KindSetsTheDefaultsOfRespawnAndKeepRunning) {
  const LaunchFile mission = parse(kValid);
  EXPECT_EQ(mission.kind, LaunchKind::Mission);  // the default
  EXPECT_FALSE(mission.processes[0].respawn.enabled);
  EXPECT_FALSE(mission.processes[0].keep_running);

  const LaunchFile field = parse(R"(
launch:
  name: vehicle
  kind: field
  processes:
    - {name: bridge, executable: /opt/cover/bin/cover-fc-bridge}
    - {name: uav0, executable: cover-uav-agent}
    - {name: ugv0, executable: cover-ugv-agent, respawn: false}
    - {name: watcher, executable: cover-fc-bridge, keep_running: false}
    - {name: mission, executable: x, ends_run: true}
)");
  EXPECT_EQ(field.kind, LaunchKind::Field);
  const auto& p = field.processes;
  EXPECT_TRUE(p[0].respawn.enabled);
  EXPECT_TRUE(p[0].keep_running) << "the bridge is kept running by default";
  EXPECT_TRUE(p[1].respawn.enabled);
  EXPECT_FALSE(p[1].keep_running);
  EXPECT_FALSE(p[2].respawn.enabled) << "an explicit respawn: false stands";
  EXPECT_FALSE(p[3].keep_running) << "an explicit keep_running: false stands";
  EXPECT_FALSE(p[4].respawn.enabled) << "the ends_run process is never respawned";

  // A standing launch may have no ends_run process: it serves until stopped.
  const LaunchFile standing = parse(
      "launch: {name: s, kind: standing, processes: [{name: p, executable: cover-fc-bridge}]}");
  EXPECT_EQ(standing.kind, LaunchKind::Standing);
  EXPECT_TRUE(standing.processes[0].keep_running);

  // In a mission the bridge stops with the run like every process.
  const LaunchFile sitl = parse(
      "launch: {name: m, processes: [{name: b, executable: cover-fc-bridge, ends_run: true}]}");
  EXPECT_FALSE(sitl.processes[0].keep_running);
}

// A sensor agent's samples are what a flying UAV waits on: its restart must be heard inside
// the failsafe ladder's hover budget (1.2 s after the death), which the general 1.0 s delay
// alone nearly used up (issue 31, item 6).
TEST(LaunchFile, SensorAgentsRespawnAfterAShortDelay) {
  const LaunchFile file = parse(R"(
launch:
  name: standing
  kind: standing
  processes:
    - {name: ugv0, executable: cover-ugv-agent}
    - {name: ugv1, executable: /opt/cover/bin/cover-ugv-agent}
    - {name: mocap, executable: cover-mocap-relay}
    - {name: uav0, executable: cover-uav-agent}
    - {name: ugv2, executable: cover-ugv-agent, respawn_delay_s: 2.0}
)");
  const auto& p = file.processes;
  for (const int i : {0, 1, 2}) {
    EXPECT_DOUBLE_EQ(p[i].respawn.delay_s, 0.1) << p[i].name;
  }
  EXPECT_DOUBLE_EQ(p[3].respawn.delay_s, 1.0) << "other processes keep the general default";
  EXPECT_DOUBLE_EQ(p[4].respawn.delay_s, 2.0) << "an explicit respawn_delay_s stands";
}

TEST(LaunchFile, KindErrors) {
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  EXPECT_TRUE(
      contains(error_of("launch: {name: a, kind: vehicle, processes: [{name: p, executable: x}]}"),
               "'vehicle' (valid: mission, standing, field)"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, processes: [{name: p, executable: x, ends_run: "
                                "true}, {name: q, executable: x, keep_running: true}]}"),
                       "keep_running: true needs launch.kind standing or field"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, kind: field, processes: [{name: p, executable: "
                                "x, ends_run: true, keep_running: true}]}"),
                       "keep_running: true and ends_run: true exclude each other"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, kind: standing, processes: [{name: p, "
                                "executable: x, ends_run: true}, {name: q, executable: x, "
                                "ends_run: true}]}"),
                       "at most one process may have ends_run: true in a standing launch"));
  EXPECT_TRUE(contains(error_of("launch: {name: a, kind: standing, processes: [{name: p, "
                                "executable: x, ends_run: true, respawn: true}]}"),
                       "respawn: true and ends_run: true"));
}

// The shipped standing system: a dying agent is respawned, the simulator ends the run.
TEST(LaunchFile, ShippedSystemIsAStandingLaunch) {
  const LaunchFile file =
      LaunchFile::load_file(std::string(COVER_SOURCE_DIR) + "/config/launch/system.yaml");
  EXPECT_EQ(file.kind, LaunchKind::Standing);
  for (const auto& process : file.processes) {
    EXPECT_EQ(process.respawn.enabled, !process.ends_run) << process.name;
    EXPECT_EQ(process.ends_run, process.name == "sim") << process.name;
  }
  // A restarted UGV agent is heard by the UAV agent in tens of milliseconds when both run
  // Cyclone DDS; a Fast DDS reader heard a restarted Cyclone writer up to 1.1 s late, past
  // the hover budget (docs/dds-vendors.md).
  const auto vendor_of = [&](const std::string& name) {
    for (const auto& process : file.processes) {
      if (process.name == name) return process.dds;
    }
    return std::string("missing");
  };
  EXPECT_EQ(vendor_of("ugv0"), "cyclone");
  EXPECT_EQ(vendor_of("ugv1"), "cyclone");
  EXPECT_EQ(vendor_of("uav0"), "cyclone");
}

// The documented example must stay a valid launch file.
TEST(LaunchFile, ShippedExampleLoads) {
  const LaunchFile file =
      LaunchFile::load_file(std::string(COVER_SOURCE_DIR) + "/config/launch/example.yaml");
  EXPECT_EQ(file.name, "scenario2");
  ASSERT_EQ(file.processes.size(), 4u);
  EXPECT_TRUE(file.processes[0].ends_run);
  EXPECT_EQ(file.processes[1].dds, "cyclone");
  EXPECT_FALSE(file.processes[1].respawn.enabled);  // the keys are shown with their defaults
}

}  // namespace
}  // namespace cover::launch

namespace cover::launch {
namespace {

// Every shipped launch file loads; the field template is a field launch whose bridge
// outlives its siblings, never auto-arms and talks to a serial autopilot; the simulated
// flight-controller launches auto-arm (simulation only) and gate the agent on the bridge.
TEST(LaunchFile, ShippedFlightControllerLaunchesLoad) {
  const std::string dir = std::string(COVER_SOURCE_DIR) + "/config/launch/";
  const LaunchFile field = LaunchFile::load_file(dir + "field_px4.yaml");
  EXPECT_EQ(field.kind, LaunchKind::Field);
  for (const auto& process : field.processes) {
    EXPECT_TRUE(process.respawn.enabled) << process.name;
    for (const auto& arg : process.args) EXPECT_NE(arg, "--auto-arm") << process.name;
    if (process.executable == "cover-fc-bridge") {
      EXPECT_TRUE(process.keep_running);
    }
  }
  EXPECT_NE(field.variables.at("autopilot_url").find("serial://"), std::string::npos);
  for (const char* name :
       {"scenario2_px4.yaml", "scenario2_ardupilot.yaml", "scenario2_px4_sitl.yaml",
        "scenario2_ardupilot_sitl.yaml", "two_uavs_px4_sitl.yaml"}) {
    const LaunchFile simulated = LaunchFile::load_file(dir + name);
    EXPECT_EQ(simulated.kind, LaunchKind::Mission) << name;
    bool bridge_auto_arms = false;
    bool agent_gated = false;
    for (const auto& process : simulated.processes) {
      const auto has = [&](const char* arg) {
        return std::find(process.args.begin(), process.args.end(), arg) != process.args.end();
      };
      if (process.executable == "cover-fc-bridge") bridge_auto_arms = has("--auto-arm");
      if (process.executable == "cover-uav-agent") agent_gated = has("--fc-bridge");
    }
    EXPECT_TRUE(bridge_auto_arms) << name;
    EXPECT_TRUE(agent_gated) << name;
  }
}

}  // namespace
}  // namespace cover::launch

namespace cover::launch {
namespace {

TEST(LaunchFile, RealtimePriority) {
  const auto file = parse(
      "launch: {name: a, processes: [{name: p, executable: x, ends_run: true, "
      "realtime_priority: 55}, {name: q, executable: x}]}");
  EXPECT_EQ(file.processes[0].realtime_priority, 55);
  EXPECT_EQ(file.processes[1].realtime_priority, 0) << "normal scheduling unless asked";
  for (const char* bad : {"100", "-1"}) {
    const std::string error =
        error_of(std::string("launch: {name: a, processes: [{name: p, executable: x, ends_run: "
                             "true, realtime_priority: ") +
                 bad + "}]}");
    EXPECT_NE(error.find("realtime_priority must be 1..99"), std::string::npos) << error;
  }
}

TEST(LaunchFile, CpuAffinity) {
  const auto file = parse(
      "launch: {name: a, processes: [{name: p, executable: x, ends_run: true, "
      "cpu_affinity: [1, 0]}, {name: q, executable: x}]}");
  EXPECT_EQ(file.processes[0].cpu_affinity, (std::vector<int>{1, 0}));
  EXPECT_TRUE(file.processes[1].cpu_affinity.empty()) << "any CPU unless asked";
  const std::pair<const char*, const char*> bad[] = {{"[-1]", "CPU -1"},
                                                     {"[1024]", "CPU 1024"},
                                                     {"[1, 1]", "CPU 1 listed twice"},
                                                     {"[x]", "cpu_affinity"},
                                                     {"1", "cpu_affinity"}};
  for (const auto& [value, reason] : bad) {
    const std::string error =
        error_of(std::string("launch: {name: a, processes: [{name: p, executable: x, ends_run: "
                             "true, cpu_affinity: ") +
                 value + "}]}");
    EXPECT_NE(error.find(reason), std::string::npos) << value << ": " << error;
  }
}

}  // namespace
}  // namespace cover::launch

namespace cover::launch {
namespace {

// `count: N` starts one description N times, {i} and {i+K} replaced in every text.
TEST(LaunchFile, CountExpandsOneProcessIntoCopies) {
  const LaunchFile file = parse(R"(
launch:
  name: fleet
  variables: {clock: lockstep}
  processes:
    - {name: sim, executable: cover-sim, ends_run: true}
    - name: "uav{i}"
      count: 3
      executable: cover-uav-agent
      args: [--id, "{i}", --port, "{i+14540}", "--task={config_dir}/uav{i}.yaml", "--clock={clock}",
             "{{i}}"]
      env: {NAME: "agent-{i}"}
      identity: "uav-agent-{i}"
)");
  ASSERT_EQ(file.processes.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    const ProcessSpec& p = file.processes[static_cast<std::size_t>(i) + 1];
    const std::string n = std::to_string(i);
    EXPECT_EQ(p.name, "uav" + n);
    EXPECT_EQ(p.args, (std::vector<std::string>{"--id", n, "--port", std::to_string(14540 + i),
                                                "--task={config_dir}/uav" + n + ".yaml",
                                                "--clock={clock}", "{{i}}"}))
        << "other placeholders and escaped braces stay for the plan";
    EXPECT_EQ(p.env.at("NAME"), "agent-" + n);
    EXPECT_EQ(p.identity, "uav-agent-" + n);
  }
}

TEST(LaunchFile, CountErrorsAreNamed) {
  const auto with = [](const std::string& process) {
    return "launch: {name: a, processes: [{name: s, executable: x, ends_run: true}, " + process +
           "]}";
  };
  const std::pair<std::string, const char*> bad[] = {
      {"{name: 'u{i}', executable: x, count: 0}", "count: 0 (valid: 1..256)"},
      {"{name: 'u{i}', executable: x, count: -2}", "count: -2 (valid: 1..256)"},
      {"{name: 'u{i}', executable: x, count: 257}", "count: 257 (valid: 1..256)"},
      {"{name: 'u{i}', executable: x, count: many}", "count: wrong type"},
      {"{name: u, executable: x, count: 2}", "must contain {i} with count: 2"},
      {"{name: u, executable: x, args: ['{i}']}",
       "uses {i}, the copy index, but the process has no count"},
      {"{name: 'u{i}', executable: x, count: 2, args: ['{i+x}']}", "the offset of {i+K}"},
      {"{name: 'u{i}', executable: x, count: 2}, {name: u1, executable: x}",
       "duplicate process name 'u1'"},
  };
  for (const auto& [process, reason] : bad) {
    const std::string error = error_of(with(process));
    EXPECT_NE(error.find(reason), std::string::npos) << process << ": " << error;
  }
}

// `count: "{uavs}"`: the fleet's size is a launch variable, a --var flag's value when given.
TEST(LaunchFile, CountFromAVariable) {
  const std::string yaml = R"(
launch:
  name: fleet
  variables: {uavs: "3", bad: "x"}
  processes:
    - {name: sim, executable: cover-sim, ends_run: true, args: ["--uavs={uavs}"]}
    - {name: "uav{i}", executable: cover-uav-agent, count: "{uavs}", args: [--id, "{i}"]}
)";
  EXPECT_EQ(parse(yaml).processes.size(), 4u);
  const LaunchFile eight =
      LaunchFile::parse(YAML::Load(yaml), "test.yaml", "/launch/dir", {{"uavs", "8"}});
  ASSERT_EQ(eight.processes.size(), 9u);
  EXPECT_EQ(eight.processes[8].args, (std::vector<std::string>{"--id", "7"}));
  const auto error_with = [&](const std::map<std::string, std::string>& overrides) {
    try {
      LaunchFile::parse(YAML::Load(yaml), "test.yaml", "/launch/dir", overrides);
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_with({{"uavs", "0"}}).find("count: 0 (valid: 1..256)"), std::string::npos);
  EXPECT_NE(error_with({{"uavs", "sixteen"}}).find("'sixteen' (from {uavs}) is not a whole number"),
            std::string::npos);
  std::string other = yaml;
  other.replace(other.find("count: \"{uavs}\""), 15, "count: \"{nope}\"");
  EXPECT_NE(error_of(other).find("'{nope}' names no variable"), std::string::npos);
}

// The shipped fleet: 1 simulator, a task manager, 16 UGV agents, 16 UAV agents each with its
// own task file.
TEST(LaunchFile, ShippedFleet16Loads) {
  const LaunchFile file =
      LaunchFile::load_file(std::string(COVER_SOURCE_DIR) + "/config/launch/fleet16.yaml");
  ASSERT_EQ(file.processes.size(), 34u);
  EXPECT_EQ(file.processes[1].name, "task_manager");
  EXPECT_EQ(file.processes[2].name, "ugv0");
  EXPECT_EQ(file.processes[17].name, "ugv15");
  EXPECT_EQ(file.processes[33].name, "uav15");
  EXPECT_NE(std::find(file.processes[33].args.begin(), file.processes[33].args.end(),
                      "{config_dir}/tasks/fleet/uav15.yaml"),
            file.processes[33].args.end());
}

}  // namespace
}  // namespace cover::launch

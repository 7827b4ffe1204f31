// From a launch file and flags to what is spawned: placeholders, --dds globs, run ids,
// executable lookup, and the leftover-segment sweep.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cover/config/config_error.hpp"
#include "cover/launch/dds_override.hpp"
#include "cover/launch/executable_lookup.hpp"
#include "cover/launch/launch_plan.hpp"
#include "cover/launch/launched_fleet.hpp"
#include "cover/launch/live_view.hpp"
#include "cover/launch/placeholders.hpp"
#include "cover/launch/recording.hpp"
#include "cover/launch/run_naming.hpp"
#include "cover/launch/security_identity.hpp"
#include "cover/launch/shm_cleanup.hpp"
#include "cover/test/scoped_env.hpp"
#include "cover/test/scratch_dir.hpp"
#include "launch_plan_support.hpp"

namespace cover::launch {
namespace {

namespace fs = std::filesystem;

std::vector<ProcessSpec> processes(std::initializer_list<const char*> names) {
  std::vector<ProcessSpec> specs;
  for (const char* name : names) {
    ProcessSpec spec;
    spec.name = name;
    spec.dds = "fastdds";
    specs.push_back(spec);
  }
  return specs;
}

TEST(LaunchDds, LaterGlobWinsWhereGlobsOverlap) {
  auto specs = processes({"sim", "ugv0", "ugv1", "uav0"});
  apply_dds_overrides(specs, {parse_dds_override("*=cyclone"), parse_dds_override("ugv*=fastdds")});
  EXPECT_EQ(specs[0].dds, "cyclone");
  EXPECT_EQ(specs[1].dds, "fastdds");
  EXPECT_EQ(specs[2].dds, "fastdds");
  EXPECT_EQ(specs[3].dds, "cyclone");

  auto reversed = processes({"sim", "ugv0"});
  apply_dds_overrides(reversed,
                      {parse_dds_override("ugv*=fastdds"), parse_dds_override("*=cyclone")});
  EXPECT_EQ(reversed[1].dds, "cyclone");
}

TEST(LaunchDds, ExactNameAndErrors) {
  auto specs = processes({"sim", "ugv0"});
  apply_dds_overrides(specs, {parse_dds_override("ugv0=cyclone")});
  EXPECT_EQ(specs[0].dds, "fastdds");
  EXPECT_EQ(specs[1].dds, "cyclone");
  EXPECT_THROW(parse_dds_override("ugv0"), std::invalid_argument);
  EXPECT_THROW(parse_dds_override("ugv0=opendds"), std::invalid_argument);
  EXPECT_THROW(parse_dds_override("=cyclone"), std::invalid_argument);
  try {
    apply_dds_overrides(specs, {parse_dds_override("uav*=cyclone")});
    FAIL() << "a pattern matching nothing must be an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("uav*"), std::string::npos) << e.what();
  }
}

TEST(LaunchPlaceholders, ExpandsAndDropsEmpty) {
  const PlaceholderValues values{{"clock", "lockstep"}, {"seed", ""}, {"run_dir", "/r"}};
  EXPECT_EQ(expand_arguments({"--scenario", "s2", "--clock={clock}", "--seed={seed}",
                              "{run_dir}/{clock}.json", "plain"},
                             values),
            (std::vector<std::string>{"--scenario", "s2", "--clock=lockstep", "/r/lockstep.json",
                                      "plain"}));
  // One empty placeholder drops the whole argument, even beside a non-empty one.
  EXPECT_EQ(expand_argument("{clock}-{seed}", values), std::nullopt);
  EXPECT_EQ(expand_argument("{{literal}} {clock}", values), "{literal} lockstep");
  EXPECT_EQ(expand_argument("", values), "");
}

TEST(LaunchPlaceholders, NamesAndMalformed) {
  EXPECT_EQ(placeholder_names("--a={x}/{y_2}{{z}}"), (std::vector<std::string>{"x", "y_2"}));
  EXPECT_THROW(placeholder_names("--a={x"), std::invalid_argument);
  EXPECT_THROW(placeholder_names("--a=x}"), std::invalid_argument);
  EXPECT_THROW(placeholder_names("--a={}"), std::invalid_argument);
  EXPECT_THROW(expand_argument("{nope}", {}), std::invalid_argument);
}

TEST(LaunchRunId, Sanitised) {
  EXPECT_EQ(sanitize_run_id("scenario-2.a b/c"), "scenario_2_a_b_c");
  EXPECT_EQ(make_run_id("scenario2", 4242), "scenario2_4242");
  EXPECT_EQ(make_run_id("demo.v-1", 7), "demo_v_1_7");
  const auto id = make_run_id("x!@#", 1);
  EXPECT_TRUE(std::all_of(id.begin(), id.end(), [](char c) { return std::isalnum(c) || c == '_'; }))
      << id;
}

TEST(LaunchRunId, DefaultRunDirIsDatedAndNeverReused) {
  const fs::path base = cover::test::scratch_dir();
  std::tm when{};
  when.tm_year = 2026 - 1900;
  when.tm_mon = 11;
  when.tm_mday = 3;
  when.tm_hour = 14;
  when.tm_min = 5;
  when.tm_sec = 9;
  when.tm_isdst = -1;
  const auto now = std::chrono::system_clock::from_time_t(std::mktime(&when));
  const std::string first = default_run_dir(base.string(), "s2", now);
  EXPECT_EQ(first, (base / "runs" / "s2_20261203-140509").string());
  fs::create_directories(first);
  EXPECT_EQ(default_run_dir(base.string(), "s2", now), first + "_2");
}

TEST(LaunchPlan, ExpandsBuiltinsAndSetsEnvironment) {
  LaunchFile file;
  file.name = "demo-1";
  file.variables = {{"clock", "lockstep"}, {"seed", ""}};
  ProcessSpec sim;
  sim.name = "sim";
  sim.executable = "cover-sim";
  sim.args = {"--run-id={run_id}",
              "--domain={domain}",
              "--seed={seed}",
              "--clock={clock}",
              "--result={run_dir}/result.json",
              "--config={config_dir}"};
  sim.env = {{"COVER_LOG_LEVEL", "debug"}};
  sim.ends_run = true;
  file.processes = {sim};
  LaunchOptions options;
  options.domain_id = 12;
  options.run_dir = "/tmp/runs/x";
  options.launcher_pid = 99;
  options.variables = {{"clock", "realtime"}};
  options.dds_overrides = {parse_dds_override("sim=cyclone")};
  const LaunchPlan plan = make_plan(file, options);
  EXPECT_EQ(plan.run_id, "demo_1_99");
  ASSERT_EQ(plan.processes.size(), 1u);
  const auto& args = plan.processes[0].args;
  ASSERT_EQ(args.size(), 5u);
  EXPECT_EQ(args[0], "--run-id=demo_1_99");
  EXPECT_EQ(args[1], "--domain=12");
  EXPECT_EQ(args[2], "--clock=realtime");
  EXPECT_EQ(args[3], "--result=/tmp/runs/x/result.json");
  EXPECT_EQ(args[4].rfind("--config=/", 0), 0u) << args[4];
  EXPECT_EQ(plan.processes[0].env,
            (std::vector<std::string>{"COVER_LOG_LEVEL=debug", "COVER_DDS=cyclone",
                                      "COVER_DDS_DOMAIN=12"}));
  EXPECT_FALSE(plan.processes[0].respawn.enabled);
  options.variables = {{"sede", "1"}};
  EXPECT_THROW(make_plan(file, options), std::invalid_argument);  // undeclared variable
  options.variables = {};
  options.domain_id = 233;
  EXPECT_THROW(make_plan(file, options), std::invalid_argument);
}

// A variable's value may use the built-in placeholders, {state_dir} among them: the
// standing system's task database goes to the user's state directory, and the plan (so the
// report) holds every value as the processes get it.
TEST(LaunchPlan, VariablesExpandTheBuiltinsStateDirAmongThem) {
  const cover::test::ScopedEnv state("XDG_STATE_HOME", "/srv/state");
  LaunchFile file = testing::parse(R"(
launch:
  name: standing
  kind: standing
  variables: {db: "{state_dir}/tasks.db", log: "{run_dir}/x.log", plain: "a"}
  processes:
    - {name: tm, executable: cover-task-manager, args: ["--db={db}", "--log={log}"]}
)");
  LaunchPlan plan = make_plan(file, testing::options_in("/runs/r"));
  EXPECT_EQ(plan.state_dir, "/srv/state/cover");
  EXPECT_EQ(plan.variables.at("db"), "/srv/state/cover/tasks.db");
  EXPECT_EQ(plan.variables.at("plain"), "a");
  EXPECT_EQ(plan.processes[0].args,
            (std::vector<std::string>{"--db=/srv/state/cover/tasks.db", "--log=/runs/r/x.log"}));

  LaunchOptions in_run = testing::options_in("/runs/r");
  in_run.variables = {{"db", "{run_dir}/tasks.db"}};
  plan = make_plan(file, in_run);
  EXPECT_EQ(plan.variables.at("db"), "/runs/r/tasks.db");
  EXPECT_EQ(plan.state_dir, "") << "no {state_dir} left: none needed";

  in_run.variables = {{"db", "{plain}/tasks.db"}};  // a variable is not a built-in
  EXPECT_THROW(make_plan(file, in_run), std::invalid_argument);
  EXPECT_THROW(testing::parse("launch: {name: a, variables: {db: '{seed}/x'}, processes: "
                              "[{name: p, executable: x, ends_run: true}]}"),
               config::ConfigError);
}

// Issue 31: system.yaml wrote cover_tasks.db into whatever folder it was started from.
TEST(LaunchPlan, ShippedSystemKeepsItsTasksInTheStateDirectory) {
  const std::string state = cover::test::scratch_path("state");
  const cover::test::ScopedEnv xdg("XDG_STATE_HOME", state.c_str());
  const LaunchFile file =
      LaunchFile::load_file(std::string(COVER_SOURCE_DIR) + "/config/launch/system.yaml");
  const LaunchPlan plan = make_plan(file, testing::options_in("/runs/system"));
  const std::string db = state + "/cover/tasks.db";
  EXPECT_EQ(plan.state_dir, state + "/cover");
  EXPECT_EQ(plan.variables.at("db"), db);
  bool found = false;
  for (const auto& process : plan.processes) {
    if (process.name != "task_manager") continue;
    found = true;
    EXPECT_EQ(process.args, std::vector<std::string>{"--db=" + db});
  }
  EXPECT_TRUE(found) << "system.yaml has no task_manager";
}

// A secure launch gives each process its identity by role, or its `identity:` key.
TEST(LaunchPlan, SecureLaunchGivesEachProcessItsIdentity) {
  EXPECT_EQ(launch_identity("a", "cover-sim", {}, ""), "sim");
  EXPECT_EQ(launch_identity("a", "/opt/bin/cover-uav-agent", {"--id", "2"}, ""), "uav-agent-2");
  EXPECT_EQ(launch_identity("a", "cover-ugv-agent", {"--source", "sim", "--id=1"}, ""),
            "ugv-agent-1");
  EXPECT_EQ(launch_identity("a", "cover-task-manager", {}, ""), "task-manager");
  EXPECT_EQ(launch_identity("a", "cover-uav-agent", {"--id", "2"}, "ground-station-0"),
            "ground-station-0");
  EXPECT_THROW(launch_identity("a", "cover-uav-agent", {}, ""), std::invalid_argument);
  EXPECT_THROW(launch_identity("a", "my-tool", {}, ""), std::invalid_argument);
  EXPECT_THROW(launch_identity("a", "cover-sim", {}, "root"), std::invalid_argument);

  LaunchFile file;
  file.name = "secure";
  file.directory = "/launch";
  file.security = "../fleet";
  ProcessSpec uav;
  uav.name = "uav0";
  uav.executable = "cover-uav-agent";
  uav.args = {"--id", "{u}"};
  uav.ends_run = true;
  file.variables = {{"u", "3"}};
  file.processes = {uav};
  LaunchOptions options;
  options.run_dir = "/tmp/runs/s";
  const LaunchPlan from_file = make_plan(file, options);
  EXPECT_EQ(from_file.security_directory, "/fleet");
  EXPECT_EQ(from_file.processes[0].identity, "uav-agent-3");
  const auto& env = from_file.processes[0].env;
  EXPECT_NE(std::find(env.begin(), env.end(), "COVER_DDS_SECURITY=/fleet"), env.end());
  EXPECT_NE(std::find(env.begin(), env.end(), "COVER_DDS_IDENTITY=uav-agent-3"), env.end());
  options.security_directory = "/elsewhere";
  EXPECT_EQ(make_plan(file, options).security_directory, "/elsewhere");
  file.security.clear();
  options.security_directory.clear();
  const LaunchPlan plain = make_plan(file, options);
  EXPECT_TRUE(plain.security_directory.empty());
  EXPECT_TRUE(plain.processes[0].identity.empty());
  EXPECT_EQ(plain.processes[0].env.size(), 2u);  // COVER_DDS, COVER_DDS_DOMAIN
}

TEST(LaunchPlan, CarriesTheRespawnPolicy) {
  LaunchFile file;
  file.name = "standing";
  ProcessSpec agent;
  agent.name = "agent";
  agent.executable = "cover-uav-agent";
  agent.respawn = {true, 0.5, 4};
  file.processes = {agent};
  LaunchOptions options;
  options.run_dir = "/tmp/runs/y";
  const LaunchPlan plan = make_plan(file, options);
  const RespawnPolicy& respawn = plan.processes.at(0).respawn;
  EXPECT_TRUE(respawn.enabled);
  EXPECT_DOUBLE_EQ(respawn.delay_s, 0.5);
  EXPECT_EQ(respawn.max_respawns, 4);
}

TEST(LaunchPlan, CarriesTheNetworkNamespace) {
  LaunchFile file;
  file.name = "wifi";
  ProcessSpec sim;
  sim.name = "sim";
  sim.executable = "cover-sim";
  sim.netns = "cwifi-sim";
  ProcessSpec agent = sim;
  agent.name = "agent";
  agent.netns.clear();
  file.processes = {sim, agent};
  LaunchOptions options;
  options.run_dir = "/tmp/runs/z";
  const LaunchPlan plan = make_plan(file, options);
  EXPECT_EQ(plan.processes.at(0).netns, "cwifi-sim");
  EXPECT_TRUE(plan.processes.at(1).netns.empty());
}

TEST(LaunchExecutable, BareNamesBesideSelfThenPath) {
  const fs::path dir = cover::test::scratch_dir();
  fs::create_directories(dir / "self");
  fs::create_directories(dir / "path");
  const auto make_exe = [](const fs::path& path) {
    std::ofstream(path) << "#!/bin/sh\n";
    chmod(path.c_str(), 0755);
  };
  make_exe(dir / "self" / "tool");
  make_exe(dir / "path" / "tool");
  make_exe(dir / "path" / "other");
  std::ofstream(dir / "path" / "not-exec") << "x";
  const std::string self = (dir / "self").string();
  const std::string path = "/nonexistent:" + (dir / "path").string();
  EXPECT_EQ(resolve_executable("tool", "/x", self, path), (dir / "self" / "tool").string());
  EXPECT_EQ(resolve_executable("other", "/x", self, path), (dir / "path" / "other").string());
  EXPECT_EQ(resolve_executable("not-exec", "/x", self, path), std::nullopt);
  EXPECT_EQ(resolve_executable("missing", "/x", self, path), std::nullopt);
  EXPECT_EQ(resolve_executable("./path/other", dir.string(), self, ""),
            (dir / "path" / "other").string());
  EXPECT_EQ(resolve_executable((dir / "self" / "tool").string(), "/x", "", ""),
            (dir / "self" / "tool").string());
}

ProcessSpec vehicle(const std::string& executable, std::vector<std::string> args) {
  ProcessSpec spec;
  spec.name = executable;
  spec.executable = executable;
  spec.args = std::move(args);
  return spec;
}

LaunchFile scenario_two_processes() {
  LaunchFile file;
  file.processes = {vehicle("cover-sim", {"--scenario", "scenario2"}),
                    vehicle("cover-ugv-agent", {"--id", "0", "--source", "sim"}),
                    vehicle("cover-ugv-agent", {"--id=1"}),
                    vehicle("../bin/cover-uav-agent", {"--id", "0", "--clock={clock}"})};
  return file;
}

TEST(LaunchedFleet, FromTheVehicleProcessesIds) {
  const auto fleet = launched_fleet(scenario_two_processes());
  ASSERT_TRUE(fleet.has_value());
  EXPECT_EQ(fleet->uavs, 1u);
  EXPECT_EQ(fleet->ugvs, 2u);
  // A bridge names a UAV too: UAV 2's bridge makes ids 0..2.
  LaunchFile with_bridge = scenario_two_processes();
  with_bridge.processes.push_back(vehicle("cover-fc-bridge", {"--id", "2"}));
  EXPECT_EQ(launched_fleet(with_bridge)->uavs, 3u);
}

TEST(LaunchedFleet, NoneWhereTheLaunchCannotKnowTheWholeFleet) {
  LaunchFile field = scenario_two_processes();
  field.kind = LaunchKind::Field;  // the other vehicles run on other hosts
  EXPECT_FALSE(launched_fleet(field).has_value());
  LaunchFile placeholder = scenario_two_processes();
  placeholder.processes[1].args = {"--id", "{ugv}"};
  EXPECT_FALSE(launched_fleet(placeholder).has_value());
  LaunchFile no_uav = scenario_two_processes();
  no_uav.processes.pop_back();
  EXPECT_FALSE(launched_fleet(no_uav).has_value());
}

TEST(LaunchedFleet, RecorderAndLiveViewBindTheLaunchedFleetElseEveryVehicle) {
  LaunchFile file = scenario_two_processes();
  add_recorder(file, "cover");
  add_live_view(file);
  const std::vector<std::string> bound{"--uavs", "1", "--ugvs", "2"};
  for (const auto& process : file.processes) {
    if (process.name != kRecorderName && process.name != kLiveViewName) continue;
    ASSERT_GE(process.args.size(), bound.size()) << process.name;
    EXPECT_TRUE(std::equal(bound.begin(), bound.end(), process.args.end() - 4)) << process.name;
  }
  EXPECT_EQ(recorder_spec("cover").args,
            (std::vector<std::string>{"record", "-o", "{run_dir}/recording.mcap"}));
  EXPECT_TRUE(live_view_spec().args.empty());
}

TEST(LaunchShm, RemovesOnlyEntriesOfTheRun) {
  const fs::path dir = cover::test::scratch_dir();
  for (const char* name : {"cover_demo_12", "cover_demo_12_seg", "cover_demo_123", "other"}) {
    std::ofstream(dir / name) << "x";
  }
  EXPECT_EQ(remove_leftover_segments("demo_12", dir.string()),
            (std::vector<std::string>{"cover_demo_12", "cover_demo_12_seg"}));
  EXPECT_TRUE(fs::exists(dir / "cover_demo_123"));
  EXPECT_TRUE(fs::exists(dir / "other"));
  EXPECT_TRUE(remove_leftover_segments("", dir.string()).empty());
}

}  // namespace
}  // namespace cover::launch

#include "cover/launch/discovery_server.hpp"

namespace cover::launch {
namespace {

bool has_env(const PlannedProcess& process, const std::string& entry) {
  return std::find(process.env.begin(), process.env.end(), entry) != process.env.end();
}

// --dds-profile server (config/dds.yaml): the launch starts the Fast DDS Discovery Server
// first, on the profile's port plus the domain, and every process is its client.
TEST(LaunchPlan, ServerProfileStartsTheDiscoveryServerFirst) {
  LaunchOptions options = testing::options_in("/tmp/run");
  options.dds_profile = "server";
  const LaunchPlan plan = make_plan(testing::parse(R"(
launch:
  name: fleet
  processes:
    - {name: sim, executable: cover-sim, ends_run: true}
    - {name: "ugv{i}", executable: cover-ugv-agent, count: 2, args: [--id, "{i}"]}
)"),
                                    options);
  ASSERT_EQ(plan.processes.size(), 4u);
  EXPECT_EQ(plan.processes[0].name, kDiscoveryServerName);
  EXPECT_EQ(plan.processes[0].executable, "fast-discovery-server");
  EXPECT_EQ(plan.processes[0].args,
            (std::vector<std::string>{"-i", "0", "-l", "127.0.0.1", "-p", "11818"}));
  for (std::size_t i = 1; i < plan.processes.size(); ++i) {
    EXPECT_TRUE(has_env(plan.processes[i], "COVER_DDS_DISCOVERY_SERVER=127.0.0.1:11818"))
        << plan.processes[i].name;
    EXPECT_TRUE(has_env(plan.processes[i], "COVER_DDS_PROFILE=server"));
  }
  options.dds_profile = "unicast";  // a profile without a server adds none
  EXPECT_EQ(make_plan(testing::parse("launch: {name: a, processes: [{name: s, executable: x, "
                                     "ends_run: true}]}"),
                      options)
                .processes.size(),
            1u);
  options.dds_profile = "nope";
  EXPECT_THROW(make_plan(testing::parse("launch: {name: a, processes: [{name: s, executable: x, "
                                        "ends_run: true}]}"),
                         options),
               config::ConfigError);
}

}  // namespace
}  // namespace cover::launch

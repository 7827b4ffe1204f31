// The page in a real browser against a real system, each test its own system and its own
// ctest entry: Debian's chromium driven by playwright-core (browser/*.mjs, harness.mjs) does
// what an operator does. Screenshots of each state are kept in the build's
// test-artifacts/ground_station/.
//  - Operator: the simulator's standing world in lockstep with a simulated PX4 (cover-sim
//    --fc px4), both UGV agents, the flight-controller bridge, the UAV agent, the task
//    manager and cover-ground-station: rows, tasks, autopilot commands, a killed agent.
//  - RecorderAndFrames: the standing world in real time, both UGV agents and the UAV agent
//    (no task: it waits on its deck): a recording
//    started and stopped from the page (the file then read by the repository's MCAP reader),
//    the 3D view in the world frame and a UGV's.
// Every process is stopped on every way out (ChildProcess's destructor; chromium dies with
// its driver, harness.mjs); every wait is a condition with a deadline scaled by
// COVER_TEST_TIME_SCALE.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "cover/recording/bag_info.hpp"
#include "cover/test/time_scale.hpp"
#include "sim_system.hpp"

namespace {

using namespace std::chrono_literals;
using cover::test::scaled;

// node on $PATH, "" when none (the browser test's driver runs in it).
std::string find_node() {
  const std::string dirs = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  for (std::size_t at = 0; at <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', at), dirs.size());
    const std::string candidate = dirs.substr(at, end - at) + "/node";
    if (end > at && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    at = end + 1;
  }
  return "";
}

std::string screenshots() {
  const std::string dir = std::string(COVER_ARTIFACT_DIR) + "/ground_station";
  std::filesystem::create_directories(dir);
  return dir;
}

// cover-ground-station of `system` on a free port; its address from its first line.
struct StationProcess {
  std::unique_ptr<cover::process::ChildProcess> child;
  std::string url;
};
StationProcess start_station(const cover::test::SimSystem& system, int domain,
                             std::vector<std::string> extra = {}) {
  cover::process::SpawnOptions options =
      cover::test::quiet("fastdds", domain, system.log_name("station"));
  options.capture_stdout = true;
  std::vector<std::string> argv{cover::test::bin("cover-ground-station"), "--port", "0",
                                "--record-dir", cover::test::scratch_dir()};
  argv.insert(argv.end(), extra.begin(), extra.end());
  StationProcess station;
  station.child = std::make_unique<cover::process::ChildProcess>(argv, options);
  if (const auto line = station.child->read_line(scaled(60000ms))) {
    std::smatch url;
    if (std::regex_search(*line, url, std::regex(R"(http://\S+)"))) station.url = url.str();
  }
  return station;
}

// Runs `node SCRIPT` against the page at `url` to its end; its lines, echoed as they come.
struct PageRun {
  int exit_code = -1;
  std::string steps;
};
PageRun run_page(const std::string& script, const std::string& url,
                 const std::vector<std::string>& extra_env = {}) {
  const std::string node_path = find_node();
  if (node_path.empty()) return {-1, "no node on PATH (scripts/setup installs Debian's nodejs)"};
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file =
      cover::test::scratch_path(std::filesystem::path(script).stem().string() + ".log");
  options.extra_env = {"GS_URL=" + url, "SCREENSHOTS=" + screenshots(),
                       std::string("CHROMIUM=") + COVER_CHROMIUM,
                       std::string("WEB_DIR=") + COVER_WEB_DIR};
  options.extra_env.insert(options.extra_env.end(), extra_env.begin(), extra_env.end());
  cover::process::ChildProcess node({node_path, script}, options);
  PageRun run;
  // One step's deadline: the longest a step waits (a flight, scaled) and more.
  while (auto line = node.read_line(scaled(400000ms))) {
    run.steps += *line + "\n";
    std::cout << "  " << *line << std::endl;
  }
  // SIGTERM first: playwright closes its browser on it.
  const auto code = node.wait(scaled(30000ms));
  run.exit_code = code ? *code : node.terminate(scaled(10000ms));
  return run;
}

void check_browser_installed() {
  ASSERT_TRUE(std::filesystem::exists(COVER_CHROMIUM))
      << COVER_CHROMIUM << " missing: scripts/setup installs Debian's chromium";
  ASSERT_TRUE(std::filesystem::exists(std::string(COVER_WEB_DIR) + "/node_modules/playwright-core"))
      << "web/node_modules missing: scripts/setup runs npm ci --prefix web";
}

}  // namespace

TEST(GroundStationBrowser, OperatorFliesAbortsArmsLandsAndSeesAKilledAgent) {
  check_browser_installed();
  constexpr int kDomain = 176;
  const std::string fc_port = std::to_string(16540 + 2 * (kDomain - 170));
  const std::string autopilot_port = std::to_string(16580 + 2 * (kDomain - 170));
  cover::test::SimSystem system(
      kDomain, "gsb",
      {"--scenario", "scenario1", "--standing", "--fc", "px4", "--fc-peer-port-base", fc_port,
       "--fc-bind-port-base", autopilot_port},
      "lockstep", scaled(60000ms));
  const auto bin = [](const char* name) { return cover::test::bin(name); };
  auto bridge = system.spawn({bin("cover-fc-bridge"), "--id", "0", "--autopilot", "px4", "--url",
                              "udpin://127.0.0.1:" + fc_port, "--clock", "lockstep", "--auto-arm"},
                             "bridge", "fastdds");
  auto agent = system.spawn({bin("cover-uav-agent"), "--id", "0", "--clock", "lockstep",
                             "--ugv-count", "2", "--fc-bridge"},
                            "uav", "fastdds");
  auto manager =
      system.spawn({bin("cover-task-manager"), "--db", cover::test::scratch_path("tasks.db")},
                   "manager", "fastdds");
  // The simulator's world: the page opens in the world frame (README's screenshot).
  auto station = start_station(system, kDomain, {"--run-id", system.run_id()});
  ASSERT_FALSE(station.url.empty())
      << "the station printed no address; " << system.log_path("station");

  const PageRun page = run_page(COVER_BROWSER_DIR "/page_test.mjs", station.url,
                                {"AGENT_PID=" + std::to_string(agent->pid())});
  EXPECT_EQ(page.exit_code, 0) << page.steps << "screenshots in " << screenshots() << ", logs in "
                               << cover::test::scratch_dir();
  EXPECT_NE(page.steps.find("ok a killed agent's row turns red within 1 s"), std::string::npos)
      << page.steps;
  EXPECT_TRUE(std::filesystem::exists(screenshots() + "/fleet.png"));

  station.child->terminate(scaled(5000ms), SIGINT);
  EXPECT_EQ(station.child->exit_code().value_or(-1), 0) << system.log_path("station");
  manager->terminate(scaled(5000ms), SIGINT);
  bridge->terminate(scaled(5000ms), SIGINT);
  agent->terminate(scaled(2000ms), SIGINT);
  system.stop(scaled(5000ms));
}

TEST(GroundStationBrowser, RecorderAndFramesFromThePage) {
  check_browser_installed();
  constexpr int kDomain = 186;
  cover::test::SimSystem system(kDomain, "gsr", {"--scenario", "scenario1", "--standing"},
                                "realtime", scaled(60000ms));
  // The world runs once its UAV's agent is there.
  auto agent = system.spawn({cover::test::bin("cover-uav-agent"), "--id", "0", "--ugv-count", "2"},
                            "uav", "fastdds");
  auto station = start_station(system, kDomain, {"--run-id", system.run_id()});
  ASSERT_FALSE(station.url.empty())
      << "the station printed no address; " << system.log_path("station");

  const PageRun page = run_page(COVER_BROWSER_DIR "/recorder_view_test.mjs", station.url);
  EXPECT_EQ(page.exit_code, 0) << page.steps << "screenshots in " << screenshots() << ", logs in "
                               << cover::test::scratch_dir();
  std::smatch file;
  ASSERT_TRUE(std::regex_search(page.steps, file, std::regex(R"(\nrecording (\S+\.mcap)\n)")))
      << page.steps;
  // The recording the page stopped: a finished MCAP file with the fleet's samples in it.
  const auto bag = cover::recording::summarize_bag(file[1]);
  EXPECT_TRUE(bag.is_mcap) << cover::recording::format_bag_summary(bag);
  EXPECT_TRUE(bag.finished) << cover::recording::format_bag_summary(bag);
  EXPECT_TRUE(bag.issues.empty()) << cover::recording::format_bag_summary(bag);
  EXPECT_GT(bag.message_count, 100u) << cover::recording::format_bag_summary(bag);
  const auto has = [&](const std::string& topic) {
    return std::any_of(bag.topics.begin(), bag.topics.end(),
                       [&](const auto& t) { return t.topic == topic && t.count > 0; });
  };
  EXPECT_TRUE(has("cover/ugv/0/imu")) << cover::recording::format_bag_summary(bag);
  EXPECT_TRUE(has("cover/sim/clock")) << cover::recording::format_bag_summary(bag);
  for (const char* shot : {"recording.png", "view3d-world.png", "view3d-ugv1.png"}) {
    EXPECT_TRUE(std::filesystem::exists(screenshots() + "/" + shot)) << shot;
  }

  station.child->terminate(scaled(5000ms), SIGINT);
  EXPECT_EQ(station.child->exit_code().value_or(-1), 0) << system.log_path("station");
  agent->terminate(scaled(5000ms), SIGINT);
  system.stop(scaled(5000ms));
}

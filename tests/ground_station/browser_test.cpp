// The page in a real browser against a real lockstep system: the simulator's standing world
// with a simulated PX4 (cover-sim --fc px4), both UGV agents, the flight-controller bridge,
// the UAV agent, the task manager and cover-ground-station, each a process; Debian's
// chromium driven by playwright-core (browser/page_test.mjs) does what an operator does.
// Screenshots of each state are kept in the build's test-artifacts/ground_station/.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include "cover/test/time_scale.hpp"
#include "sim_system.hpp"

namespace {

using namespace std::chrono_literals;
using cover::test::scaled;

constexpr int kDomain = 176;

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

}  // namespace

TEST(GroundStationBrowser, OperatorFliesAbortsArmsLandsAndSeesAKilledAgent) {
  ASSERT_TRUE(std::filesystem::exists(COVER_CHROMIUM))
      << COVER_CHROMIUM << " missing: scripts/setup installs Debian's chromium";
  ASSERT_TRUE(std::filesystem::exists(std::string(COVER_WEB_DIR) + "/node_modules/playwright-core"))
      << "web/node_modules missing: scripts/setup runs npm ci --prefix web";
  const std::string fc_port = std::to_string(16540 + 2 * (kDomain - 170));
  const std::string autopilot_port = std::to_string(16580 + 2 * (kDomain - 170));
  cover::test::SimSystem system(
      kDomain, "gsb",
      {"--scenario", "scenario1", "--standing", "--fc", "px4", "--fc-peer-port-base", fc_port,
       "--fc-bind-port-base", autopilot_port},
      "lockstep");
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
  cover::process::SpawnOptions station_options =
      cover::test::quiet("fastdds", kDomain, system.log_name("station"));
  station_options.capture_stdout = true;
  cover::process::ChildProcess station(
      {bin("cover-ground-station"), "--port", "0", "--record-dir", cover::test::scratch_dir()},
      station_options);
  const auto line = station.read_line(scaled(20000ms));
  ASSERT_TRUE(line.has_value()) << "the station printed no address; " << system.log_path("station");
  std::smatch url;
  ASSERT_TRUE(std::regex_search(*line, url, std::regex(R"(http://\S+)"))) << *line;

  const std::string shots = std::string(COVER_ARTIFACT_DIR) + "/ground_station";
  std::filesystem::create_directories(shots);
  cover::process::SpawnOptions node_options;
  node_options.capture_stdout = true;
  node_options.log_file = cover::test::scratch_path("page_test.log");
  node_options.extra_env = {
      "GS_URL=" + url.str(), "SCREENSHOTS=" + shots, "AGENT_PID=" + std::to_string(agent->pid()),
      std::string("CHROMIUM=") + COVER_CHROMIUM, std::string("WEB_DIR=") + COVER_WEB_DIR};
  const std::string node_path = find_node();
  ASSERT_FALSE(node_path.empty()) << "no node on PATH (scripts/setup installs Debian's nodejs)";
  cover::process::ChildProcess node({node_path, COVER_PAGE_TEST}, node_options);
  std::string steps;
  while (auto step = node.read_line(scaled(240000ms))) {
    steps += *step + "\n";
    std::cout << "  " << *step << std::endl;
  }
  const auto code = node.wait(scaled(30000ms));
  EXPECT_EQ(code.value_or(-1), 0) << steps << "screenshots in " << shots << ", logs in "
                                  << cover::test::scratch_dir();
  EXPECT_NE(steps.find("ok a killed agent's row turns red within 1 s"), std::string::npos) << steps;
  EXPECT_TRUE(std::filesystem::exists(shots + "/fleet.png"));

  station.terminate(scaled(5000ms), SIGINT);
  EXPECT_EQ(station.exit_code().value_or(-1), 0) << system.log_path("station");
  manager->terminate(scaled(5000ms), SIGINT);
  bridge->terminate(scaled(5000ms), SIGINT);
  agent->terminate(scaled(2000ms), SIGINT);
  system.stop(scaled(5000ms));
}

// Scenario 2 in realtime over a field-like WiFi network (scripts/wifi-sim): the simulator,
// each UGV agent and the UAV agent in their own network namespace on one bridge, 10 % of
// the UDP datagrams lost on every link, a bandwidth cap, multicast dropped, DDS discovery
// by the unicast peers of the `wifi` profile (config/dds.yaml). On Fast DDS, Cyclone DDS
// and both mixed. Needs root; skipped (with the reason) where network namespaces are not
// available.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/process/scoped_setup.hpp"
#include "cover/test/scratch_dir.hpp"
#include "launch_run.hpp"
#include "process_support.hpp"

namespace {

namespace fs = std::filesystem;
using cover::test::shm_entries;

constexpr std::chrono::seconds kRunTimeout{300};
constexpr std::chrono::seconds kScriptTimeout{60};
constexpr int kSkipped = 77;  // scripts/wifi-sim check: not root, or no network namespaces
constexpr double kMaxLandingErrorM = 0.05;

// This process's names for scripts/wifi-sim (--run TAG): its namespaces, bridge and veth
// ends are its own, so a crashed earlier run or another test's network is never touched.
std::string run_tag() {
  char tag[8];
  std::snprintf(tag, sizeof tag, "%x", static_cast<unsigned>(getpid()) & 0xffffffu);
  return tag;
}

// config/launch/scenario2_wifi.yaml with this run's namespaces (cwifiTAG-NODE for
// cwifi-NODE), written to the test's scratch folder.
std::string launch_file_for_run(const std::string& tag) {
  std::ifstream in(std::string(COVER_CONFIG_DIR) + "/launch/scenario2_wifi.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "netns: cwifi-", to = "netns: cwifi" + tag + "-";
  for (auto at = yaml.find(from); at != std::string::npos; at = yaml.find(from, at + to.size())) {
    yaml.replace(at, from.size(), to);
  }
  const std::string path = cover::test::scratch_path("scenario2_wifi.yaml");
  std::ofstream(path) << yaml;
  return path;
}

// Every test sets the network up and tears it down (`wifi-sim down`, and segments of its
// run in /dev/shm), whether it passes, fails or throws.
class WifiNetwork : public ::testing::Test {
 protected:
  void SetUp() override {
    if (geteuid() != 0) GTEST_SKIP() << "not root: network namespaces need root";
    const auto check = cover::process::run_command(
        {COVER_WIFI_SIM, "check"}, cover::test::scratch_path("wifi_check.log"), kScriptTimeout);
    if (check.exit_code == kSkipped) GTEST_SKIP() << check.output;
    ASSERT_EQ(check.exit_code, 0) << check.output;
    network_ = std::make_unique<cover::process::ScopedSetup>(
        std::vector<std::string>{COVER_WIFI_SIM, "--run", tag_, "up", "--loss-percent", "10"},
        std::vector<std::string>{COVER_WIFI_SIM, "--run", tag_, "down"},
        cover::test::scratch_path("wifi_up.log"));
    ASSERT_TRUE(network_->ok()) << network_->up_result().output;
  }

  void TearDown() override {
    network_.reset();
    if (run_id_.empty()) return;
    for (const auto& entry : fs::directory_iterator("/dev/shm")) {
      if (entry.path().filename().string().find(run_id_) != std::string::npos) {
        ADD_FAILURE() << "left in /dev/shm: " << entry.path();
        fs::remove_all(entry.path());
      }
    }
  }

  // cover-launch with config/launch/scenario2_wifi.yaml in realtime; its --json report.
  nlohmann::json fly(const std::vector<std::string>& dds_flags, int domain) {
    const auto claim = cover::test::claim_domain(domain);
    cover::bench::LaunchRequest request;
    request.launch_file = launch_file_for_run(tag_);
    request.domain = domain;
    request.run_dir = cover::test::scratch_dir() / ("cover_wifi_" + std::to_string(domain));
    request.flags = {"--clock", "realtime"};
    request.flags.insert(request.flags.end(), dds_flags.begin(), dds_flags.end());
    cover::process::SpawnOptions options;
    options.capture_stdout = true;
    cover::process::ChildProcess launcher(cover::bench::launch_argv(request), options);
    run_id_ = "scenario2_wifi_" + std::to_string(launcher.pid());
    std::string text;
    while (const auto line = launcher.read_line(kRunTimeout)) text += *line + "\n";
    exit_code_ = launcher.wait(kRunTimeout).value_or(-1);
    auto report = nlohmann::json::parse(text, nullptr, false);
    EXPECT_FALSE(report.is_discarded()) << text << "\nlogs: " << request.run_dir;
    return report.is_discarded() ? nlohmann::json::object() : report;
  }

  void expect_success(const std::vector<std::string>& dds_flags, int domain) {
    const auto before = shm_entries();
    const nlohmann::json run = fly(dds_flags, domain);
    ASSERT_EQ(exit_code_, 0) << run.dump(2);
    EXPECT_TRUE(run.value("success", false)) << run.dump(2);
    const auto landing = run.find("landing_error_m");
    ASSERT_TRUE(landing != run.end() && landing->is_number()) << run.dump(2);
    EXPECT_LE(landing->get<double>(), kMaxLandingErrorM) << run.dump(2);
    EXPECT_EQ(run.value("clock", ""), "realtime");
    ASSERT_TRUE(run.contains("processes"));
    for (const auto& p : run["processes"]) {
      EXPECT_NE(kill(p["pid"].get<int>(), 0), 0) << p["name"] << " still runs";
    }
    for (const std::string& name : shm_entries()) {
      if (before.count(name)) continue;
      EXPECT_TRUE(name.find("fastrtps") == std::string::npos) << "Fast DDS file left: " << name;
    }
    std::cout << "[wifi] landing_error_m " << landing->get<double>() << " duration_s "
              << run.value("duration_s", std::nan("")) << "\n";
  }

 private:
  const std::string tag_ = run_tag();
  std::unique_ptr<cover::process::ScopedSetup> network_;
  std::string run_id_;
  int exit_code_ = -1;
};

TEST_F(WifiNetwork, ScenarioTwoRealtimeOverLossyLinkOnFastDds) {
  expect_success({}, 171);
}

TEST_F(WifiNetwork, ScenarioTwoRealtimeOverLossyLinkOnCyclone) {
  expect_success({"--dds", "*=cyclone"}, 172);
}

TEST_F(WifiNetwork, ScenarioTwoRealtimeOverLossyLinkMixed) {
  expect_success({"--dds", "ugv*=cyclone"}, 173);
}

}  // namespace

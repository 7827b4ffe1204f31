// DDS discovery over the field-like WiFi (scripts/wifi-sim), as `cover-bench discovery
// --wifi` measures it, at its smallest: two processes, each in its own network namespace
// (10 % of received UDP datagrams lost, 10mbit), with simple discovery where the bridge
// passes multicast, unicast peers where it drops it, and the Fast DDS Discovery Server in a
// third namespace in both. Every reader and writer of both matches within the deadline, and
// the run leaves none of its namespaces or nftables tables behind. Needs root; skipped
// (with the reason) where network namespaces are not available, as WifiNetwork.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/process/scoped_setup.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"

namespace {

using namespace std::chrono_literals;

constexpr int kSkipped = 77;  // scripts/wifi-sim check: not root, or no network namespaces
// Last process start -> every reader matched, per cell. Measured for two processes on the
// loaded 2-core VM (docs/benchmarks.md): medians 0.1-1.6 s, 4.6 s the worst of 24 runs (a
// lost discovery datagram waits for the next announcement or heartbeat).
constexpr std::chrono::milliseconds kMatchDeadline = 15s;
// The whole bench: four cells, a network up and down per multicast mode, and the bench's own
// 60 s give-up per cell should a process never match.
constexpr std::chrono::milliseconds kBenchTimeout = 300s;

// The lines of `argv`'s output (`ip netns list`, `nft list tables`).
std::string output_of(const std::vector<std::string>& argv, const std::string& log) {
  return cover::process::run_command(argv, cover::test::scratch_path(log), 30s).output;
}

// scripts/wifi-sim's run tag of the bench with pid `pid` (its names contain it).
std::string tag_of(pid_t pid) {
  char tag[8];
  std::snprintf(tag, sizeof tag, "%x", static_cast<unsigned>(pid) & 0xffffffu);
  return tag;
}

TEST(WifiNetworkDiscovery, TwoProcessesMatchOverLossyLinkByEachProfile) {
#ifndef COVER_BENCH
  GTEST_SKIP() << "built without cover-bench";
#else
  if (geteuid() != 0) GTEST_SKIP() << "not root: network namespaces need root";
  const auto check = cover::process::run_command({COVER_WIFI_SIM, "check"},
                                                 cover::test::scratch_path("wifi_check.log"), 60s);
  if (check.exit_code == kSkipped) GTEST_SKIP() << check.output;
  ASSERT_EQ(check.exit_code, 0) << check.output;

  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = cover::test::scratch_path("bench.log");  // stderr
  cover::process::ChildProcess bench({COVER_BENCH, "discovery", "--wifi", "--processes", "2",
                                      "--repeats", "1", "--multicast", "both", "--json"},
                                     options);
  const std::string tag = tag_of(bench.pid());
  std::string text;
  const auto deadline = std::chrono::steady_clock::now() + cover::test::scaled(kBenchTimeout);
  while (std::chrono::steady_clock::now() < deadline) {
    if (const auto line = bench.read_line(1s)) {
      text += *line + "\n";
    } else if (bench.wait(100ms)) {
      break;
    }
  }
  while (const auto line = bench.read_line(1s)) text += *line + "\n";  // what it wrote last
  // Out of time: SIGTERM, on which the bench stops its processes and takes the network down.
  std::optional<int> exit_code = bench.wait(0ms);
  if (!exit_code) exit_code = bench.terminate(60s);
  EXPECT_EQ(exit_code, 0) << text << "\nstderr: " << options.log_file;

  const auto report = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << text;
  std::set<std::string> cells;
  for (const auto& row : report.at("rows")) {
    const std::string cell = row.at("profile").get<std::string>() +
                             (row.at("multicast").get<bool>() ? " multicast" : " no multicast");
    cells.insert(cell);
    EXPECT_EQ(row.at("network"), "wifi") << cell;
    EXPECT_EQ(row.at("loss_percent"), 10) << cell;
    ASSERT_TRUE(row.at("median_s").is_number()) << cell << ": not measured\n" << row.dump();
    const double seconds = row.at("median_s").get<double>();
    EXPECT_GE(seconds, 0.0) << cell;
    EXPECT_LE(seconds, std::chrono::duration<double>(cover::test::scaled(kMatchDeadline)).count())
        << cell;
    std::cout << "[wifi discovery] " << cell << ": " << seconds << " s\n";
  }
  EXPECT_EQ(cells, (std::set<std::string>{"simple multicast", "server multicast",
                                          "unicast no multicast", "server no multicast"}));

  // Nothing of this run's network is left: its namespaces (cwifiTAG-NODE), its bridge and
  // veth ends (cwbTAG, cwTAG-NODE) and its nftables table (cover_wifi_TAG).
  const std::string namespaces = output_of({"/usr/bin/env", "ip", "netns", "list"}, "netns.log");
  EXPECT_EQ(namespaces.find("cwifi" + tag + "-"), std::string::npos) << namespaces;
  const std::string links = output_of({"/usr/bin/env", "ip", "-o", "link"}, "links.log");
  EXPECT_EQ(links.find("cwb" + tag), std::string::npos) << links;
  EXPECT_EQ(links.find("cw" + tag + "-"), std::string::npos) << links;
  const std::string tables = output_of({"/usr/bin/env", "nft", "list", "tables"}, "nft.log");
  EXPECT_EQ(tables.find("cover_wifi_" + tag), std::string::npos) << tables;
#endif
}

}  // namespace

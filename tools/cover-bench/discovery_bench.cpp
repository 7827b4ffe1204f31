// cover-bench discovery: how long a fleet's processes take to find each other. N processes
// (one per vehicle) each write one topic and read their two neighbours' (a ring: every
// reader needs a writer of another process, as a UAV agent needs its two UGVs'); the time
// from the start of the last process to the moment every reader and writer of every process
// is matched, for 2, 8, 16, 32 processes, per discovery profile of config/dds.yaml:
// `simple` (the default: multicast on lo), `unicast` (simple discovery with multicast off,
// unicast to the host's participant ports) and `server` (a Fast DDS Discovery Server,
// started here first, as cover-launch does). Fast DDS only: the server serves Fast DDS
// clients. Each process is `cover-bench discovery-peer`.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/dds/domain_claim.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/child_process.hpp"
#include "not_measured.hpp"

namespace {

using nlohmann::json;
using namespace std::chrono_literals;

std::int64_t monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

// One peer: matched when its writer has both neighbours' readers and each of its readers
// a writer. Prints "matched <CLOCK_MONOTONIC ns>" then waits to be stopped.
int peer(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench discovery-peer: one process of `cover-bench discovery`"};
  int id = 0;
  int count = 2;
  int timeout_s = 60;
  app.add_option("--id", id)->required();
  app.add_option("--count", count)->required()->check(CLI::Range(2, 256));
  app.add_option("--timeout", timeout_s);
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  auto options = cover::dds::ParticipantOptions::load_file(
      cover::config::default_config_dir() + "/dds.yaml", cover::dds::profile_from_environment(""));
  options = cover::dds::apply_environment(options);
  options.participant_name = "cover-bench-discovery-" + std::to_string(id);
  cover::dds::Participant participant(options);
  const auto topic = [&](int k) {
    return cover::dds::topics::ugv_imu(static_cast<std::uint32_t>((k + count) % count));
  };
  auto writer = participant.make_writer(topic(id));
  auto next = participant.make_reader(topic(id + 1), [](const cover::msg::UgvImu&) {});
  auto previous = participant.make_reader(topic(id - 1), [](const cover::msg::UgvImu&) {});
  const std::chrono::milliseconds timeout(1000 * timeout_s);
  // Each waits while the others may match meanwhile: the last to match ends the three.
  if (!writer.wait_for_readers(2, timeout) || !next.wait_for_writers(1, timeout) ||
      !previous.wait_for_writers(1, timeout)) {
    return 1;
  }
  std::printf("matched %lld\n", static_cast<long long>(monotonic_ns()));
  std::fflush(stdout);
  // Matched: it stays (its writer and readers matched for the others) until stopped.
  pause();  // until the bench's SIGTERM
  return 0;
}

struct Cell {
  std::string profile;
  int processes = 0;
  std::optional<double> seconds;  // last start -> every process matched
  std::string why;                // when not measured
};

// One measurement: `count` peers on `profile`, the server first when it has one.
Cell measure(const std::string& self, const std::string& profile, int count) {
  Cell cell{profile, count, std::nullopt, ""};
  const auto claim = cover::dds::DomainClaim::claim_any(150, 220);
  std::vector<std::string> env{"COVER_DDS=fastdds",
                               "COVER_DDS_DOMAIN=" + std::to_string(claim.domain()),
                               "COVER_DDS_PROFILE=" + (profile == "simple" ? "" : profile)};
  std::unique_ptr<cover::process::ChildProcess> server;
  if (profile == "server") {
    const auto options = cover::dds::ParticipantOptions::load_file(
        cover::config::default_config_dir() + "/dds.yaml", "server");
    auto address = cover::dds::parse_server_address(options.discovery_server);
    address.port += claim.domain();
    cover::process::SpawnOptions spawn;
    spawn.capture_stdout = true;
    server = std::make_unique<cover::process::ChildProcess>(
        // env looks the server up on $PATH and execs it: the pid stays the server's.
        std::vector<std::string>{"/usr/bin/env", "fast-discovery-server", "-i", "0", "-l",
                                 address.address, "-p", std::to_string(address.port)},
        spawn);
    const auto line = server->read_line(10s);  // "### Server is running ###"
    if (!line || line->find("running") == std::string::npos) {
      cell.why = "fast-discovery-server did not start (apt-get install fastdds-tools)";
      return cell;
    }
    env.push_back("COVER_DDS_DISCOVERY_SERVER=" + address.address + ":" +
                  std::to_string(address.port));
  }
  std::vector<std::unique_ptr<cover::process::ChildProcess>> peers;
  std::int64_t last_start_ns = 0;
  for (int k = 0; k < count; ++k) {
    cover::process::SpawnOptions spawn;
    spawn.extra_env = env;
    spawn.capture_stdout = true;
    last_start_ns = monotonic_ns();
    peers.push_back(std::make_unique<cover::process::ChildProcess>(
        std::vector<std::string>{self, "discovery-peer", "--id", std::to_string(k), "--count",
                                 std::to_string(count)},
        spawn));
  }
  std::int64_t last_matched_ns = 0;
  for (auto& p : peers) {
    const auto line = p->read_line(70s);
    long long stamp = 0;
    if (!line || std::sscanf(line->c_str(), "matched %lld", &stamp) != 1) {
      cell.why = "a process never matched within 60 s";
      break;
    }
    last_matched_ns = std::max<std::int64_t>(last_matched_ns, stamp);
  }
  for (auto& p : peers) p->terminate(2000ms);
  if (server) server->terminate(2000ms);
  if (cell.why.empty())
    cell.seconds = std::max<double>(0.0, (last_matched_ns - last_start_ns) * 1e-9);
  return cell;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench discovery: last process start -> every reader matched"};
  std::vector<int> counts{2, 8, 16, 32};
  std::vector<std::string> profiles{"simple", "unicast", "server"};
  int repeats = 3;
  bool as_json = false;
  app.add_option("--processes", counts, "fleet sizes (processes)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--profiles", profiles, "simple | unicast | server")
      ->delimiter(',')
      ->check(CLI::IsMember({"simple", "unicast", "server"}))
      ->capture_default_str();
  app.add_option("--repeats", repeats, "runs per cell (the median is reported)")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  app.add_flag("--json", as_json);
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  for (const int count : counts) {
    if (count < 2 || count > 64) {
      std::cerr << "cover-bench discovery: --processes " << count
                << ": 2..64 (a process needs another to match)\n";
      return 2;
    }
  }
  const std::string self = "/proc/self/exe";
  char path[4096];
  const ssize_t length = readlink(self.c_str(), path, sizeof(path) - 1);
  if (length <= 0) return 1;
  const std::string executable(path, static_cast<std::size_t>(length));

  cover::bench::NotMeasured missing;
  json rows = json::array();
  std::printf("%-8s %9s %10s %10s %10s\n", "profile", "processes", "median s", "min s", "max s");
  for (const auto& profile : profiles) {
    for (const int count : counts) {
      std::vector<double> seconds;
      std::string why;
      for (int r = 0; r < repeats; ++r) {
        const Cell cell = measure(executable, profile, count);
        if (cell.seconds)
          seconds.push_back(*cell.seconds);
        else
          why = cell.why;
      }
      if (seconds.empty()) {
        missing.add(profile + " x " + std::to_string(count) + ": " + why);
        rows.push_back({{"profile", profile}, {"processes", count}, {"median_s", nullptr}});
        continue;
      }
      std::sort(seconds.begin(), seconds.end());
      const double median = seconds[seconds.size() / 2];
      rows.push_back({{"profile", profile},
                      {"processes", count},
                      {"median_s", median},
                      {"min_s", seconds.front()},
                      {"max_s", seconds.back()},
                      {"runs", seconds.size()}});
      if (!as_json) {
        std::printf("%-8s %9d %10.3f %10.3f %10.3f\n", profile.c_str(), count, median,
                    seconds.front(), seconds.back());
        std::fflush(stdout);
      }
    }
  }
  if (as_json) std::cout << json{{"rows", rows}}.dump(2) << "\n";
  return missing.exit_code("discovery");
}

const cover::bench::Registrar kRegistrar{
    "discovery", "last process start -> every reader matched: simple / unicast / server, 2..32",
    &run};
const cover::bench::Registrar kPeerRegistrar{
    "discovery-peer", "(internal) one process of `cover-bench discovery`", &peer};

}  // namespace

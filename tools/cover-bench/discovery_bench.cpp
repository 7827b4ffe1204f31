// cover-bench discovery: how long a fleet's processes take to find each other. N processes
// (one per vehicle) each write one topic and read their two neighbours' (a ring: every
// reader needs a writer of another process, as a UAV agent needs its two UGVs'); the time
// from the start of the last process to the moment every reader and writer of every process
// is matched, for 2, 8, 16, 32 processes, per discovery profile of config/dds.yaml:
// `simple` (the default: multicast), `unicast` (simple discovery with multicast off,
// unicast to peers) and `server` (a Fast DDS Discovery Server, started here first, as
// cover-launch does; Fast DDS clients only). On this host's loopback, or with --wifi over
// scripts/wifi-sim's emulated WiFi: each process in its own network namespace (a vehicle),
// the server in another (the ground station's), loss and a rate cap on every link, the
// bridge passing or dropping multicast. Each process is `cover-bench discovery-peer`.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
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
#include "cover/process/shutdown_signal.hpp"
#include "discovery_wifi.hpp"
#include "not_measured.hpp"

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
using cover::process::ChildProcess;
using namespace std::chrono_literals;

// A peer that has not matched by then never will: the bench gives up on the run.
constexpr int kPeerTimeout_s = 60;
constexpr auto kRunTimeout = std::chrono::seconds(kPeerTimeout_s + 10);
constexpr int kExitInterrupted = 130;

std::int64_t monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

// One peer: matched when its writer has both neighbours' readers and each of its readers
// a writer. Prints "matched <CLOCK_MONOTONIC ns>" then waits to be stopped. --interface
// and --peers replace the profile's: the network the bench made decides them.
int peer(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench discovery-peer: one process of `cover-bench discovery`"};
  int id = 0;
  int count = 2;
  int timeout_s = kPeerTimeout_s;
  std::string interface_name;
  std::vector<std::string> peers;
  app.add_option("--id", id)->required();
  app.add_option("--count", count)->required()->check(CLI::Range(2, 256));
  app.add_option("--timeout", timeout_s);
  app.add_option("--interface", interface_name, "network interface (default: the profile's)");
  app.add_option("--peers", peers, "unicast peers, IPv4 (default: the profile's)")->delimiter(',');
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  auto options = cover::dds::ParticipantOptions::load_file(
      cover::config::default_config_dir() + "/dds.yaml", cover::dds::profile_from_environment(""));
  options = cover::dds::apply_environment(options);
  if (!interface_name.empty()) options.interface_name = interface_name;
  if (!peers.empty()) options.peers = peers;
  options.validate();
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

// What one row measures: a profile on a vendor, on loopback (wifi null) or the WiFi.
struct Setup {
  std::string profile;  // simple | unicast | server
  std::string vendor;   // fastdds | cyclone
  const cover::bench::DiscoveryWifi* wifi = nullptr;
};

struct Cell {
  std::optional<double> seconds;  // last start -> every process matched
  std::string why;                // when not measured
};

// config/dds.yaml's profile for a row: over the WiFi, unicast is the `wifi` profile (its
// interface; its peers replaced by the addresses in use).
std::string dds_profile(const Setup& setup) {
  if (setup.profile == "simple") return "";
  if (setup.profile == "unicast" && setup.wifi) return "wifi";
  return setup.profile;
}

// The next line of `child`, or nullopt at `deadline`, at its end or on Ctrl-C.
std::optional<std::string> read_line_until(ChildProcess& child, Clock::time_point deadline) {
  while (!cover::process::ShutdownSignal::requested()) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left <= 0ms) return std::nullopt;
    if (auto line = child.read_line(std::min<std::chrono::milliseconds>(left, 200ms))) return line;
    if (child.wait(0ms)) return std::nullopt;  // it ended without the line
  }
  return std::nullopt;
}

// The Fast DDS Discovery Server for `domain` (its port shifted by the domain, as
// cover-launch does), in the WiFi's server namespace when there is one. Null with `why` set
// when it did not start; `address` is "IPv4:port" for its clients.
std::unique_ptr<ChildProcess> start_server(const Setup& setup, int domain, std::string& address,
                                           std::string& why) {
  const auto options = cover::dds::ParticipantOptions::load_file(
      cover::config::default_config_dir() + "/dds.yaml", "server");
  auto server = cover::dds::parse_server_address(options.discovery_server);
  server.port += domain;
  if (setup.wifi) server.address = setup.wifi->address(cover::bench::DiscoveryWifi::kServerNode);
  // env looks the server up on $PATH and execs it: the pid stays the server's.
  std::vector<std::string> argv{
      "/usr/bin/env", "fast-discovery-server", "-i", "0",
      "-l",           server.address,          "-p", std::to_string(server.port)};
  if (setup.wifi) argv = setup.wifi->in_node(cover::bench::DiscoveryWifi::kServerNode, argv);
  cover::process::SpawnOptions spawn;
  spawn.capture_stdout = true;
  auto child = std::make_unique<ChildProcess>(argv, spawn);
  const auto line = read_line_until(*child, Clock::now() + 10s);  // "### Server is running ###"
  if (!line || line->find("running") == std::string::npos) {
    why = "fast-discovery-server did not start (apt-get install fastdds-tools)";
    return nullptr;
  }
  address = server.address + ":" + std::to_string(server.port);
  return child;
}

std::vector<std::string> peer_argv(const std::string& self, const Setup& setup, int k, int count) {
  std::vector<std::string> argv{self,      "discovery-peer",     "--id", std::to_string(k),
                                "--count", std::to_string(count)};
  if (!setup.wifi) return argv;
  argv.insert(argv.end(), {"--interface", cover::bench::DiscoveryWifi::kInterface});
  if (setup.profile == "unicast") {
    // Only the addresses in use: one that nobody answers costs each send to it ARP's timeout.
    std::string peers;
    for (int j = 0; j < count; ++j) {
      peers += (j ? "," : "") + setup.wifi->address(cover::bench::DiscoveryWifi::process_node(j));
    }
    argv.insert(argv.end(), {"--peers", peers});
  }
  return setup.wifi->in_node(cover::bench::DiscoveryWifi::process_node(k), argv);
}

// One measurement: `count` peers of `setup`, the server first when it has one.
Cell measure(const std::string& self, const Setup& setup, int count) {
  Cell cell;
  const auto claim = cover::dds::DomainClaim::claim_any(150, 220);
  std::vector<std::string> env{"COVER_DDS=" + setup.vendor,
                               "COVER_DDS_DOMAIN=" + std::to_string(claim.domain()),
                               "COVER_DDS_PROFILE=" + dds_profile(setup)};
  std::unique_ptr<ChildProcess> server;
  if (setup.profile == "server") {
    std::string address;
    server = start_server(setup, claim.domain(), address, cell.why);
    if (!server) return cell;
    env.push_back("COVER_DDS_DISCOVERY_SERVER=" + address);
  }
  std::vector<std::unique_ptr<ChildProcess>> peers;
  std::int64_t last_start_ns = 0;
  for (int k = 0; k < count; ++k) {
    cover::process::SpawnOptions spawn;
    spawn.extra_env = env;
    spawn.capture_stdout = true;
    last_start_ns = monotonic_ns();
    peers.push_back(std::make_unique<ChildProcess>(peer_argv(self, setup, k, count), spawn));
  }
  std::int64_t last_matched_ns = 0;
  const auto deadline = Clock::now() + kRunTimeout;
  for (auto& p : peers) {
    const auto line = read_line_until(*p, deadline);
    long long stamp = 0;
    if (!line || std::sscanf(line->c_str(), "matched %lld", &stamp) != 1) {
      cell.why = cover::process::ShutdownSignal::requested()
                     ? "interrupted"
                     : "a process never matched within " + std::to_string(kPeerTimeout_s) + " s";
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

// The 1-minute load average (other work on the machine slows discovery down).
double load_average() {
  std::ifstream in("/proc/loadavg");
  double one_minute = -1.0;
  in >> one_minute;
  return one_minute;
}

struct Options {
  std::vector<int> counts{2, 8, 16, 32};
  std::vector<std::string> profiles{"simple", "unicast", "server"};
  std::vector<std::string> vendors{"fastdds"};
  int repeats = 3;
  bool as_json = false;
  bool wifi = false;
  std::string multicast = "both";
  cover::bench::WifiLink link;
};

// Why a row is left out, or "" when it runs. Over the WiFi, simple discovery runs where
// multicast passes (it has nothing else), unicast peers where it does not (where they are
// the choice); the server serves Fast DDS clients only.
std::string left_out(const Setup& setup, bool multicast) {
  if (setup.profile == "server" && setup.vendor != "fastdds")
    return "the Discovery Server serves Fast DDS clients only";
  if (!setup.wifi) return "";
  if (setup.profile == "simple" && !multicast) return "simple discovery needs multicast";
  if (setup.profile == "unicast" && multicast) return "unicast peers: measured without multicast";
  return "";
}

// `repeats` runs of one cell, sorted; `why` says why a run measured nothing.
std::vector<double> run_cell(const std::string& self, const Setup& setup, int count, int repeats,
                             std::string& why) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats && !cover::process::ShutdownSignal::requested(); ++r) {
    const Cell cell = measure(self, setup, count);
    if (cell.seconds)
      seconds.push_back(*cell.seconds);
    else
      why = cell.why;
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds;
}

// A cell's row: median, min and max over its runs (null when none measured), the load.
json cell_row(const Setup& setup, bool multicast, const Options& o, int count,
              const std::vector<double>& seconds) {
  json row{{"network", setup.wifi ? "wifi" : "lo"},
           {"multicast", setup.wifi ? json(multicast) : json(nullptr)},
           {"vendor", setup.vendor},
           {"profile", setup.profile},
           {"processes", count},
           {"runs", seconds.size()},
           {"load_average", load_average()},
           {"median_s", nullptr}};
  if (setup.wifi) row.update({{"loss_percent", o.link.loss_percent}, {"rate", o.link.rate}});
  if (!seconds.empty()) {
    row.update({{"median_s", seconds[seconds.size() / 2]},
                {"min_s", seconds.front()},
                {"max_s", seconds.back()}});
  }
  return row;
}

void print_row(const std::string& network, const json& row) {
  const auto text = [&](const char* key) { return row.at(key).get<std::string>(); };
  std::printf("%-19s %-8s %-8s %9d ", network.c_str(), text("vendor").c_str(),
              text("profile").c_str(), row.at("processes").get<int>());
  if (row.at("median_s").is_null()) {
    std::printf("%10s\n", "not measured");
  } else {
    std::printf("%10.3f %8.3f %8.3f %5d %6.1f\n", row.at("median_s").get<double>(),
                row.at("min_s").get<double>(), row.at("max_s").get<double>(),
                row.at("runs").get<int>(), row.at("load_average").get<double>());
  }
  std::fflush(stdout);
}

// The rows of one network: loopback, or the WiFi with multicast passed or dropped. A cell
// with fewer runs than asked for is named in `missing`.
void measure_network(const std::string& self, const Options& o,
                     const cover::bench::DiscoveryWifi* wifi, bool multicast, json& rows,
                     cover::bench::NotMeasured& missing) {
  const std::string network = wifi ? (multicast ? "wifi, multicast" : "wifi, no multicast") : "lo";
  for (const auto& vendor : o.vendors) {
    for (const auto& profile : o.profiles) {
      const Setup setup{profile, vendor, wifi};
      if (const std::string why = left_out(setup, multicast); !why.empty()) {
        if (!o.as_json)
          std::printf("# %s %s on %s: not run: %s\n", vendor.c_str(), profile.c_str(),
                      network.c_str(), why.c_str());
        continue;
      }
      for (const int count : o.counts) {
        std::string why;
        const auto seconds = run_cell(self, setup, count, o.repeats, why);
        if (cover::process::ShutdownSignal::requested()) return;
        if (static_cast<int>(seconds.size()) < o.repeats) {
          missing.add(network + " " + vendor + " " + profile + " x " + std::to_string(count) +
                      ": " + std::to_string(o.repeats - seconds.size()) + " of " +
                      std::to_string(o.repeats) + " runs: " + why);
        }
        rows.push_back(cell_row(setup, multicast, o, count, seconds));
        if (!o.as_json) print_row(network, rows.back());
      }
    }
  }
}

// Every cell over the WiFi, one network per multicast mode (sized for the largest cell).
// False when the network could not be set up.
bool measure_wifi(const std::string& self, Options o, json& rows,
                  cover::bench::NotMeasured& missing) {
  std::vector<bool> modes;
  if (o.multicast != "drop") modes.push_back(true);
  if (o.multicast != "pass") modes.push_back(false);
  const int largest = *std::max_element(o.counts.begin(), o.counts.end());
  for (const bool multicast : modes) {
    if (cover::process::ShutdownSignal::requested()) break;
    o.link.multicast = multicast;
    const cover::bench::DiscoveryWifi wifi(o.link, largest);
    if (!wifi.ok()) {
      std::cerr << "cover-bench discovery: scripts/wifi-sim up failed (root needed):\n"
                << wifi.output();
      return false;
    }
    measure_network(self, o, &wifi, multicast, rows, missing);
  }
  return true;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"cover-bench discovery: last process start -> every reader matched"};
  Options o;
  app.add_option("--processes", o.counts, "fleet sizes (processes)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--profiles", o.profiles, "simple | unicast | server")
      ->delimiter(',')
      ->check(CLI::IsMember({"simple", "unicast", "server"}))
      ->capture_default_str();
  app.add_option("--vendors", o.vendors, "fastdds | cyclone (the server: Fast DDS only)")
      ->delimiter(',')
      ->check(CLI::IsMember({"fastdds", "cyclone"}))
      ->capture_default_str();
  app.add_option("--repeats", o.repeats, "runs per cell (median, min, max reported)")
      ->check(CLI::Range(1, 20))
      ->capture_default_str();
  app.add_flag("--json", o.as_json);
  app.add_flag("--wifi", o.wifi,
               "over scripts/wifi-sim's emulated WiFi: a network namespace per process and one "
               "for the server (root); simple where multicast passes, unicast where not");
  app.add_option("--multicast", o.multicast,
                 "with --wifi: the bridge passes multicast, drops it, or both in turn")
      ->check(CLI::IsMember({"pass", "drop", "both"}))
      ->capture_default_str();
  app.add_option("--loss-percent", o.link.loss_percent, "with --wifi: UDP loss on every link (%)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  app.add_option("--rate", o.link.rate, "with --wifi: bandwidth cap per namespace (tc tbf rate)")
      ->capture_default_str();
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  for (const int count : o.counts) {
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
  // Ctrl-C stops the runs, then the network comes down (the destructors): no namespace,
  // veth, bridge or nftables table is left behind.
  cover::process::ShutdownSignal::install();

  cover::bench::NotMeasured missing;
  json rows = json::array();
  if (!o.as_json) {
    std::printf("%-19s %-8s %-8s %9s %10s %8s %8s %5s %6s\n", "network", "vendor", "profile",
                "processes", "median s", "min s", "max s", "runs", "load");
  }
  if (!o.wifi) {
    measure_network(executable, o, nullptr, true, rows, missing);
  } else if (!measure_wifi(executable, o, rows, missing)) {
    return 1;
  }
  if (cover::process::ShutdownSignal::requested()) {
    std::cerr << "cover-bench discovery: interrupted\n";
    return kExitInterrupted;
  }
  if (o.as_json) std::cout << json{{"rows", rows}}.dump(2) << "\n";
  return missing.exit_code("discovery");
}

const cover::bench::Registrar kRegistrar{
    "discovery",
    "last process start -> every reader matched: simple / unicast / server, 2..32, lo or --wifi",
    &run, /*handles_shutdown=*/true};
const cover::bench::Registrar kPeerRegistrar{
    "discovery-peer", "(internal) one process of `cover-bench discovery`", &peer,
    /*handles_shutdown=*/true};

}  // namespace

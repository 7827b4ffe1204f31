// cover-bench e2e: the system as processes (cover-launch -> cover-sim, UGV and UAV agents).
//  latency:  realtime Scenario 2, sensor-to-command latency as cover-sim measures it (it
//            stamps each relative state it publishes; the command computed from it names
//            that stamp when it comes back), per DDS mix, plain and with DDS-Security
//            (secure: every process authenticated, its data encrypted);
//  lockstep: Scenarios 2 and 4 in lockstep, simulated seconds per wall second.
#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/process/child_process.hpp"

namespace {

#ifdef COVER_LAUNCH
constexpr const char* kLaunch = COVER_LAUNCH;
#else
constexpr const char* kLaunch = "cover-launch";
#endif
#ifdef COVER_CLI
constexpr const char* kCoverCli = COVER_CLI;
#else
constexpr const char* kCoverCli = "cover";
#endif

struct DdsMix {
  const char* name;
  std::vector<std::string> flags;       // cover-launch --dds flags
  const char* secure_vendor = nullptr;  // DDS-Security with a fleet of this vendor; null: plain
};

// fastdds / cyclone: every process on one vendor; mixed: the simulator and UGV agents on
// Cyclone, the UAV agent on Fast DDS, so the measured path crosses vendors both ways.
const std::vector<DdsMix> kMixes = {
    {"fastdds", {"--dds", "*=fastdds"}},
    {"cyclone", {"--dds", "*=cyclone"}},
    {"mixed", {"--dds", "*=cyclone", "--dds", "uav*=fastdds"}},
    // A secure fleet runs one vendor (docs/security.md): no secure mixed row.
    {"fastdds", {"--dds", "*=fastdds"}, "fastdds"},
    {"cyclone", {"--dds", "*=cyclone"}, "cyclone"},
};

// A fresh fleet directory for a secure row (removed after the run); empty on failure.
std::string make_fleet(const char* vendor) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("cover_e2e_fleet_" + std::string(vendor) + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  cover::process::SpawnOptions options;
  options.log_file = dir.string() + ".log";
  cover::process::ChildProcess init(
      {kCoverCli, "security", "init", dir.string(), "--vendor", vendor}, options);
  if (init.wait(std::chrono::minutes(1)) != 0) {
    std::cerr << "cover-bench e2e: cover security init failed; see " << options.log_file << "\n";
    return "";
  }
  std::filesystem::remove(options.log_file);
  return dir.string();
}

nlohmann::json run_launch(const std::string& scenario, std::vector<std::string> flags, int domain) {
  const std::filesystem::path run_dir =
      std::filesystem::temp_directory_path() / ("cover_e2e_" + std::to_string(getpid()));
  std::filesystem::remove_all(run_dir);
  std::vector<std::string> argv = {
      kLaunch,
      cover::config::default_config_dir() + "/launch/" + scenario + ".yaml",
      "--json",
      "--domain",
      std::to_string(domain),
      "--run-dir",
      run_dir.string()};
  argv.insert(argv.end(), flags.begin(), flags.end());
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  // The launcher's own log lines would bury the table: keep them in a file (kept when the
  // run produced no result, to show why).
  const std::string launcher_log = run_dir.string() + ".log";
  options.log_file = launcher_log;
  cover::process::ChildProcess child(argv, options);
  std::string out;
  while (const auto line = child.read_line(std::chrono::minutes(5))) out += *line + "\n";
  child.wait(std::chrono::minutes(1));
  std::filesystem::remove_all(run_dir);
  const nlohmann::json result = nlohmann::json::parse(out, nullptr, false);
  if (result.is_object() && result.contains("success")) {
    std::filesystem::remove(launcher_log);
  } else {
    std::cerr << "cover-bench e2e: " << scenario << " gave no result; see " << launcher_log << "\n";
  }
  return result;
}

double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"The system as processes: sensor-to-command latency and lockstep speed"};
  bool json = false;
  int domain = 180;
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--domain", domain, "first DDS domain to use (one per run)")
      ->capture_default_str();
  std::string method;
  app.add_option("--method", method,
                 "the UAV agents' method: " + cover::bench::joined_method_names(" | ") +
                     " (default: sampc.yaml's mode)")
      ->check(CLI::IsMember(cover::bench::method_names()));
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  // The launch files pass {method} to every UAV agent as --method.
  const std::vector<std::string> method_flags =
      method.empty() ? std::vector<std::string>{}
                     : std::vector<std::string>{"--var", "method=" + method};

  nlohmann::json out{{"latency", nlohmann::json::array()}, {"lockstep", nlohmann::json::array()}};
  for (const DdsMix& mix : kMixes) {
    std::vector<std::string> flags = mix.flags;
    flags.insert(flags.end(), {"--clock", "realtime"});
    flags.insert(flags.end(), method_flags.begin(), method_flags.end());
    const std::string fleet = mix.secure_vendor ? make_fleet(mix.secure_vendor) : "";
    if (!fleet.empty()) flags.insert(flags.end(), {"--security", fleet});
    const nlohmann::json r = run_launch("scenario2", flags, domain++);
    if (!fleet.empty()) std::filesystem::remove_all(fleet);
    const nlohmann::json latency =
        r.is_object() && r.contains("latency_ms") ? r["latency_ms"] : nlohmann::json::object();
    out["latency"].push_back({{"mix", mix.name},
                              {"secure", mix.secure_vendor != nullptr},
                              {"success", r.is_object() && r.value("success", false)},
                              {"p50_ms", number(latency, "p50")},
                              {"p99_ms", number(latency, "p99")},
                              {"samples", latency.value("samples", 0)}});
  }
  for (const char* scenario : {"scenario2", "scenario4"}) {
    std::vector<std::string> flags = {"--dds", "ugv*=cyclone"};
    flags.insert(flags.end(), method_flags.begin(), method_flags.end());
    const nlohmann::json r = run_launch(scenario, flags, domain++);
    out["lockstep"].push_back({{"scenario", scenario},
                               {"success", r.is_object() && r.value("success", false)},
                               {"speed_factor", number(r, "speed_factor")}});
  }
  if (json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf(
        "sensor-to-command latency, realtime Scenario 2 (relative state out -> command in)\n");
    for (const auto& l : out["latency"]) {
      std::printf("  %-8s %-6s p50 %.3f ms  p99 %.3f ms  (%d samples)%s\n",
                  l["mix"].get<std::string>().c_str(), l["secure"].get<bool>() ? "secure" : "plain",
                  l["p50_ms"].get<double>(), l["p99_ms"].get<double>(), l["samples"].get<int>(),
                  l["success"].get<bool>() ? "" : "  MISSION FAILED");
    }
    std::printf("lockstep (UGV agents on Cyclone, the rest on Fast DDS)\n");
    for (const auto& l : out["lockstep"]) {
      std::printf("  %-10s %s, %.1fx real time\n", l["scenario"].get<std::string>().c_str(),
                  l["success"].get<bool>() ? "success" : "FAILED", l["speed_factor"].get<double>());
    }
  }
  return 0;
}

const cover::bench::Registrar registrar{"e2e", "missions as processes: latency and lockstep speed",
                                        &run};

}  // namespace

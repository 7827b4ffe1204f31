// cover-bench e2e: the system as processes (cover-launch -> cover-sim, UGV and UAV agents).
//  latency:  realtime Scenario 2, sensor-to-command latency as cover-sim measures it (it
//            stamps each relative state it publishes; the command computed from it names
//            that stamp when it comes back), per DDS mix, plain and with DDS-Security
//            (secure: every process authenticated, its data encrypted; one-vendor mixes
//            only, docs/security.md); beside each plain mix, its floor measured during that
//            run (concurrent_floor.hpp says why): round trips between two bare processes on the
//            simulator's and the UAV agent's vendors, paced at 100 Hz, out on the relative state's
//            QoS and back on the command's (the two hops of the path with no work at either end),
//            and the latency as a multiple of it;
//  lockstep: Scenarios 2 and 4 in lockstep, simulated seconds per wall second, on Fast DDS
//            (UGV agents on Cyclone) and Scenario 2 on Cyclone DDS alone;
//  and in every run the UAV agent's measurement -> command (its control trace: inputs taken
//  to command out, median and p99 over the steps SAMPC flew).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "concurrent_floor.hpp"
#include "cover/launch/launch_file.hpp"
#include "cover/process/child_process.hpp"
#include "cover_binary.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"
#include "vendor_mix.hpp"

namespace {

// A secure fleet runs one vendor: the mixes whose processes all share one.
bool one_vendor(const cover::bench::VendorMix& mix) {
  return std::strcmp(mix.sim, mix.ugv) == 0 && std::strcmp(mix.sim, mix.uav) == 0;
}

// A fresh fleet directory for a secure row (the caller removes it); empty on failure.
std::string make_fleet(const char* vendor) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("cover_e2e_fleet_" + std::string(vendor) + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  cover::process::SpawnOptions options;
  options.log_file = dir.string() + ".log";
  cover::process::ChildProcess init(
      {cover::bench::cover_binary("cover"), "security", "init", dir.string(), "--vendor", vendor},
      options);
  if (init.wait(std::chrono::minutes(1)) != 0) {
    std::cerr << "cover-bench e2e: cover security init failed; see " << options.log_file << "\n";
    return "";
  }
  std::filesystem::remove(options.log_file);
  return dir.string();
}

// The floor's pace: the simulator publishes a relative state per control period (100 Hz in
// the scenario files' mission.yaml).
constexpr double kFloorRateHz = 100.0;

// The launch file's process `name` (a default one, normal scheduling on any CPU, if none).
cover::launch::ProcessSpec process_in(const cover::launch::LaunchFile& file,
                                      const std::string& name) {
  for (const auto& spec : file.processes) {
    if (spec.name == name) return spec;
  }
  return {};
}

// The mix's floor, measured while its run flies: paced round trips simulator vendor -> UAV
// agent vendor -> back, on the relative state's and the command's QoS, each end scheduled
// (and the pong pinned) as the launch file schedules the simulator and the UAV agent (a
// floor at normal scheduling beside a run at SCHED_FIFO would compare the schedulers, not
// the path).
std::unique_ptr<cover::bench::ConcurrentFloor> start_floor(const cover::bench::VendorMix& mix,
                                                           const std::string& launch_name,
                                                           int domain) {
  const auto file =
      cover::launch::LaunchFile::load_file(cover::bench::launch_file_path(launch_name));
  cover::bench::PingPongOptions options;
  options.ping_vendor = cover::dds::parse_vendor(mix.sim);
  options.pong_vendor = cover::dds::parse_vendor(mix.uav);
  options.domain_id = domain;
  options.prefix = "cover_bench/e2e_floor_" + std::to_string(getpid());
  options.ping_qos = cover::dds::sensor_qos();
  options.pong_qos = cover::dds::command_qos();
  options.ping_realtime_priority = process_in(file, "sim").realtime_priority;
  const cover::launch::ProcessSpec uav = process_in(file, "uav0");
  options.pong_realtime_priority = uav.realtime_priority;
  options.pong_cpu_affinity = uav.cpu_affinity;
  auto floor = std::make_unique<cover::bench::ConcurrentFloor>(options, kFloorRateHz);
  if (floor->failed())
    std::cerr << "cover-bench e2e: the floor of " << mix.name << " did not start\n";
  return floor;
}

// NaN (not measured) when either side is missing.
double ratio(double value, const nlohmann::json& floor, const char* key) {
  if (!floor.is_object() || !floor[key].is_number() || floor[key].get<double>() <= 0.0) {
    return NAN;
  }
  return value / floor[key].get<double>();
}

// NaN (not measured) when the report has no such number.
double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

// How a launch ended, for a reason: its report may be empty (the launcher gave none).
std::string outcome(const nlohmann::json& report) {
  if (report.empty()) return "the launch gave no result";
  return report.value("success", false) ? "the mission succeeded" : "the mission failed";
}

std::string row_name(const cover::bench::VendorMix& mix, bool secure) {
  return std::string(mix.name) + (secure ? " secure" : " plain");
}

// A JSON figure for the table: formatted, or "not measured" for null.
std::string text(const nlohmann::json& value, const char* format) {
  return cover::bench::figure_text(format, value.is_number() ? value.get<double>() : NAN);
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
  bool with_floor = true;
  app.add_flag("!--no-floor", with_floor,
               "skip each plain mix's floor (paced round trips measured during its run)");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  // The launch files pass {method} to every UAV agent as --method.
  const std::vector<std::string> method_flags =
      method.empty() ? std::vector<std::string>{}
                     : std::vector<std::string>{"--var", "method=" + method};

  nlohmann::json out{{"latency", nlohmann::json::array()}, {"lockstep", nlohmann::json::array()}};
  cover::bench::NotMeasured missing;
  for (const bool secure : {false, true}) {
    for (const cover::bench::VendorMix& mix : cover::bench::vendor_mixes()) {
      if (secure && !one_vendor(mix)) continue;
      std::vector<std::string> flags = cover::bench::launch_dds_flags(mix);
      flags.insert(flags.end(), {"--clock", "realtime"});
      flags.insert(flags.end(), method_flags.begin(), method_flags.end());
      const std::string fleet = secure ? make_fleet(mix.sim) : "";
      if (!fleet.empty()) flags.insert(flags.end(), {"--security", fleet});
      auto running_floor =
          secure || !with_floor ? nullptr : start_floor(mix, "scenario2", domain++);
      const nlohmann::json r = cover::bench::run_launch("scenario2", flags, domain++, "e2e");
      const nlohmann::json floor = running_floor ? running_floor->stop() : nullptr;
      if (!fleet.empty()) std::filesystem::remove_all(fleet);
      const nlohmann::json latency =
          r.is_object() && r.contains("latency_ms") ? r["latency_ms"] : nlohmann::json::object();
      const int samples = latency.value("samples", 0);
      const double p50 = samples > 0 ? number(latency, "p50") : NAN;
      const double p99 = samples > 0 ? number(latency, "p99") : NAN;
      if (samples == 0) {
        missing.add("latency, " + row_name(mix, secure) +
                    ": the run reported no sensor-to-command sample (" + outcome(r) + ")");
      }
      if (running_floor && !floor.is_object()) {
        missing.add("floor of " + std::string(mix.name) + ": no round trip came back");
      }
      out["latency"].push_back(
          {{"mix", mix.name},
           {"secure", secure},
           {"success", r.is_object() && r.value("success", false) && (!secure || !fleet.empty())},
           {"p50_ms", cover::bench::figure_json(p50)},
           {"p99_ms", cover::bench::figure_json(p99)},
           {"samples", samples},
           {"floor", floor},
           {"p50_over_floor", cover::bench::figure_json(ratio(p50, floor, "p50_ms"))},
           {"p99_over_floor", cover::bench::figure_json(ratio(p99, floor, "p99_ms"))},
           {"command_median_us", cover::bench::figure_json(number(r, "command_median_us"))},
           {"command_p99_us", cover::bench::figure_json(number(r, "command_p99_us"))}});
    }
  }
  struct LockstepRun {
    const char* scenario;
    const char* dds;  // the launch's --dds
    const char* mix;  // as the table names it
  };
  for (const LockstepRun& run :
       {LockstepRun{"scenario2", "ugv*=cyclone", "fastdds, UGV agents cyclone"},
        LockstepRun{"scenario4", "ugv*=cyclone", "fastdds, UGV agents cyclone"},
        LockstepRun{"scenario2", "*=cyclone", "cyclone"}}) {
    std::vector<std::string> flags = {"--dds", run.dds};
    flags.insert(flags.end(), method_flags.begin(), method_flags.end());
    const nlohmann::json r = cover::bench::run_launch(run.scenario, flags, domain++, "e2e");
    const double speed = number(r, "speed_factor");
    if (!(speed > 0.0)) {
      missing.add(std::string("lockstep ") + run.scenario + " (" + run.mix +
                  "): the run reported no speed factor (" + outcome(r) + ")");
    }
    out["lockstep"].push_back(
        {{"scenario", run.scenario},
         {"mix", run.mix},
         {"success", r.is_object() && r.value("success", false)},
         {"speed_factor", cover::bench::figure_json(speed > 0.0 ? speed : NAN)},
         {"startup_s", cover::bench::figure_json(number(r, "startup_s"))},
         {"command_median_us", cover::bench::figure_json(number(r, "command_median_us"))},
         {"command_p99_us", cover::bench::figure_json(number(r, "command_p99_us"))}});
  }
  if (json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf(
        "sensor-to-command latency, realtime Scenario 2 (relative state out -> command in)\n");
    for (const auto& l : out["latency"]) {
      std::printf("  %-8s %-6s p50 %s  p99 %s  (%d samples)%s\n",
                  l["mix"].get<std::string>().c_str(), l["secure"].get<bool>() ? "secure" : "plain",
                  text(l["p50_ms"], "%.3f ms").c_str(), text(l["p99_ms"], "%.3f ms").c_str(),
                  l["samples"].get<int>(), l["success"].get<bool>() ? "" : "  MISSION FAILED");
      std::printf("  %-15s measurement -> command p50 %s  p99 %s\n", "",
                  text(l["command_median_us"], "%.1f us").c_str(),
                  text(l["command_p99_us"], "%.1f us").c_str());
      if (l["floor"].is_object()) {
        const auto& f = l["floor"];
        std::printf("  %-15s floor p50 %.3f ms  p99 %.3f ms  (%d round trips)  -> %s / %s\n", "",
                    f["p50_ms"].get<double>(), f["p99_ms"].get<double>(), f["samples"].get<int>(),
                    text(l["p50_over_floor"], "%.2fx").c_str(),
                    text(l["p99_over_floor"], "%.2fx").c_str());
      }
    }
    std::printf("lockstep\n");
    for (const auto& l : out["lockstep"]) {
      std::printf(
          "  %-10s %-28s %s, %s real time (after %s of start-up); measurement -> command p50 %s  "
          "p99 %s\n",
          l["scenario"].get<std::string>().c_str(), l["mix"].get<std::string>().c_str(),
          l["success"].get<bool>() ? "success" : "FAILED", text(l["speed_factor"], "%.1fx").c_str(),
          text(l["startup_s"], "%.3f s").c_str(), text(l["command_median_us"], "%.1f us").c_str(),
          text(l["command_p99_us"], "%.1f us").c_str());
    }
  }
  return missing.exit_code("e2e");
}

const cover::bench::Registrar registrar{"e2e", "missions as processes: latency and lockstep speed",
                                        &run};

}  // namespace

// cover-bench e2e: the system as processes (cover-launch -> cover-sim, UGV and UAV agents).
//  latency:  realtime Scenario 2, sensor-to-command latency as cover-sim measures it (it
//            stamps each relative state it publishes; the command computed from it names
//            that stamp when it comes back), per DDS mix;
//  lockstep: Scenarios 2 and 4 in lockstep, simulated seconds per wall second.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "launch_run.hpp"
#include "vendor_mix.hpp"

namespace {

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
  for (const cover::bench::VendorMix& mix : cover::bench::vendor_mixes()) {
    std::vector<std::string> flags = cover::bench::launch_dds_flags(mix);
    flags.insert(flags.end(), {"--clock", "realtime"});
    flags.insert(flags.end(), method_flags.begin(), method_flags.end());
    const nlohmann::json r = cover::bench::run_launch("scenario2", flags, domain++, "e2e");
    const nlohmann::json latency =
        r.is_object() && r.contains("latency_ms") ? r["latency_ms"] : nlohmann::json::object();
    out["latency"].push_back({{"mix", mix.name},
                              {"success", r.is_object() && r.value("success", false)},
                              {"p50_ms", number(latency, "p50")},
                              {"p99_ms", number(latency, "p99")},
                              {"samples", latency.value("samples", 0)}});
  }
  for (const char* scenario : {"scenario2", "scenario4"}) {
    std::vector<std::string> flags = {"--dds", "ugv*=cyclone"};
    flags.insert(flags.end(), method_flags.begin(), method_flags.end());
    const nlohmann::json r = cover::bench::run_launch(scenario, flags, domain++, "e2e");
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
      std::printf("  %-8s p50 %.3f ms  p99 %.3f ms  (%d samples)%s\n",
                  l["mix"].get<std::string>().c_str(), l["p50_ms"].get<double>(),
                  l["p99_ms"].get<double>(), l["samples"].get<int>(),
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

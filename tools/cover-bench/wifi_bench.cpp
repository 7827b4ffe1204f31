// cover-bench wifi: Scenario 2 in realtime over scripts/wifi-sim's field-like network (one
// network namespace per process, UDP loss on every link, a bandwidth cap, no multicast,
// DDS discovery by the unicast peers of the `wifi` profile), per DDS vendor mix and seed.
// Rows as `cover-bench faults` (fault_row.hpp), fault "wifi_loss". Needs root.
#include <unistd.h>

#include <algorithm>
#include <cmath>
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
#include "cover/process/scoped_setup.hpp"
#include "fault_row.hpp"

namespace {

#ifdef COVER_LAUNCH
constexpr const char* kLaunch = COVER_LAUNCH;
#else
constexpr const char* kLaunch = "cover-launch";
#endif
#ifdef COVER_WIFI_SIM
constexpr const char* kWifiSim = COVER_WIFI_SIM;
#else
constexpr const char* kWifiSim = "scripts/wifi-sim";
#endif

constexpr std::chrono::minutes kRunTimeout{5};
constexpr std::chrono::seconds kScriptTimeout{60};
// A touchdown faster than this is a crash (the bound for a failsafe landing).
constexpr double kSafeTouchdownMS = 1.0;

struct Mix {
  const char* name;
  std::vector<std::string> flags;  // cover-launch --dds flags
};

// mixed: the UGV agents on Cyclone, the simulator and the UAV agent on Fast DDS, so the
// UGV IMU crosses vendors (as tests/integration/wifi_network_test.cpp).
const std::vector<Mix> kMixes = {
    {"fastdds", {"--dds", "*=fastdds"}},
    {"cyclone", {"--dds", "*=cyclone"}},
    {"mixed", {"--dds", "ugv*=cyclone"}},
};

struct Flags {
  bool json = false;
  int seeds = 10;
  int loss_percent = 10;
  std::string rate = "10mbit";
  int domain = 190;
};

nlohmann::json fly(const Mix& mix, int seed, int domain) {
  const std::filesystem::path run_dir =
      std::filesystem::temp_directory_path() / ("cover_wifi_bench_" + std::to_string(getpid()));
  std::filesystem::remove_all(run_dir);
  std::vector<std::string> argv = {
      kLaunch,
      cover::config::default_config_dir() + "/launch/scenario2_wifi.yaml",
      "--json",
      "--clock",
      "realtime",
      "--seed",
      std::to_string(seed),
      "--domain",
      std::to_string(domain),
      "--run-dir",
      run_dir.string()};
  argv.insert(argv.end(), mix.flags.begin(), mix.flags.end());
  cover::process::SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = run_dir.string() + ".log";
  cover::process::ChildProcess child(argv, options);
  std::string out;
  while (const auto line = child.read_line(kRunTimeout)) out += *line + "\n";
  child.wait(kRunTimeout);
  const nlohmann::json result = nlohmann::json::parse(out, nullptr, false);
  if (result.is_object() && result.value("success", false)) {
    std::filesystem::remove_all(run_dir);
    std::filesystem::remove(options.log_file);
  } else {
    std::cerr << "cover-bench wifi: " << mix.name << " seed " << seed << " failed; logs in "
              << run_dir.string() << "\n";
  }
  return result.is_object() ? result : nlohmann::json::object();
}

// The report's number under `key`, NaN when it has none.
double number_or_nan(const nlohmann::json& j, const char* key) {
  if (j.contains(key) && j[key].is_number()) return j[key].get<double>();
  return std::nan("");
}

// Completed: the mission succeeded. Landed safely: it did not, but the simulator saw a
// touchdown no faster than kSafeTouchdownMS. Anything else counts as crashed: a run
// that cannot show it landed softly is not given the benefit of the doubt.
cover::bench::FaultRow row_of(const Mix& mix, int seed, const nlohmann::json& r) {
  cover::bench::FaultRow row;
  row.fault = "wifi_loss";
  row.mix = mix.name;
  row.seed = seed;
  row.time_to_failsafe_ms = number_or_nan(r, "time_to_failsafe_ms");
  row.touchdown_speed_m_s = number_or_nan(r, "touchdown_speed_m_s");
  row.landing_error_m = number_or_nan(r, "landing_error_m");
  row.outcome = "crashed";
  if (r.value("success", false)) {
    row.outcome = "completed";
  } else if (row.touchdown_speed_m_s <= kSafeTouchdownMS) {  // false for NaN
    row.outcome = "landed_safely";
  }
  row.detail = r.value("status", std::string());
  return row;
}

nlohmann::json mix_summary(const Mix& mix, const std::vector<cover::bench::FaultRow>& rows,
                           const std::vector<double>& latency_p99_ms) {
  int completed = 0;
  int runs = 0;
  double worst_landing_m = 0.0;
  for (const auto& row : rows) {
    if (row.mix != mix.name) continue;
    ++runs;
    if (row.outcome == "completed") ++completed;
    if (std::isfinite(row.landing_error_m)) {
      worst_landing_m = std::max(worst_landing_m, row.landing_error_m);
    }
  }
  const double worst_p99 = latency_p99_ms.empty()
                               ? 0.0
                               : *std::max_element(latency_p99_ms.begin(), latency_p99_ms.end());
  return {{"mix", mix.name},
          {"runs", runs},
          {"completed", completed},
          {"max_landing_error_m", worst_landing_m},
          {"max_latency_p99_ms", worst_p99}};
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"Scenario 2 in realtime over a lossy, multicast-free emulated WiFi (root)"};
  Flags flags;
  app.add_flag("--json", flags.json, "print JSON {rows, summary} instead of a table");
  app.add_option("--seeds", flags.seeds, "seeds per vendor mix (1..)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--loss-percent", flags.loss_percent, "UDP loss on every link (%)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  app.add_option("--rate", flags.rate, "bandwidth cap per namespace (tc tbf rate)")
      ->capture_default_str();
  app.add_option("--domain", flags.domain, "first DDS domain (one per run)")
      ->check(CLI::Range(0, 232))
      ->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  const auto log = std::filesystem::temp_directory_path() / "cover_wifi_bench_net.log";
  const cover::process::ScopedSetup network(
      {kWifiSim, "up", "--loss-percent", std::to_string(flags.loss_percent), "--rate", flags.rate},
      {kWifiSim, "down"}, log.string());
  if (!network.ok()) {
    std::cerr << "cover-bench wifi: scripts/wifi-sim up failed (root needed):\n"
              << network.up_result().output;
    return 1;
  }
  std::vector<cover::bench::FaultRow> rows;
  nlohmann::json summary = nlohmann::json::array();
  int domain = flags.domain;
  for (const Mix& mix : kMixes) {
    std::vector<double> latency_p99_ms;
    for (int seed = 1; seed <= flags.seeds; ++seed) {
      const nlohmann::json r = fly(mix, seed, domain);
      domain = domain >= 232 ? flags.domain : domain + 1;
      rows.push_back(row_of(mix, seed, r));
      if (r.contains("latency_ms")) latency_p99_ms.push_back(r["latency_ms"].value("p99", 0.0));
      if (!flags.json) {
        const auto& row = rows.back();
        std::printf(
            "%-8s seed %2d  %-13s landing %s\n", mix.name, seed, row.outcome.c_str(),
            std::isfinite(row.landing_error_m) ? std::to_string(row.landing_error_m).c_str() : "-");
      }
    }
    summary.push_back(mix_summary(mix, rows, latency_p99_ms));
  }
  nlohmann::json out = cover::bench::rows_json(rows);
  out["summary"] = summary;
  out["loss_percent"] = flags.loss_percent;
  out["rate"] = flags.rate;
  if (flags.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    for (const auto& s : summary) std::printf("%s\n", s.dump().c_str());
  }
  return 0;
}

const cover::bench::Registrar registrar{
    "wifi", "Scenario 2 over emulated lossy WiFi (netns, root): fault rows per vendor mix", &run};

}  // namespace

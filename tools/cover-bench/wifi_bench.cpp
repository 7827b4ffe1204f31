// cover-bench wifi: Scenario 2 in realtime over scripts/wifi-sim's field-like network, per
// DDS vendor mix and seed (wifi_runs.hpp): the `wifi_loss` rows of `cover-bench faults`,
// with a per-mix summary and the loss and rate as options. Needs root.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "fault_row.hpp"
#include "not_measured.hpp"
#include "wifi_runs.hpp"

namespace {

using cover::bench::VendorMix;
using cover::bench::WifiRun;

nlohmann::json mix_summary(const VendorMix& mix, const std::vector<WifiRun>& runs) {
  int completed = 0;
  int count = 0;
  // Over the runs that measured them; NaN (null) when none did.
  double worst_landing_m = NAN;
  double worst_p99_ms = NAN;
  const auto worst = [](double so_far, double value) {
    return std::isfinite(value) && !(so_far >= value) ? value : so_far;
  };
  for (const WifiRun& run : runs) {
    if (run.row.mix != mix.name) continue;
    ++count;
    if (run.row.outcome == "completed") ++completed;
    worst_landing_m = worst(worst_landing_m, run.row.landing_error_m);
    worst_p99_ms = worst(worst_p99_ms, run.latency_p99_ms);
  }
  return {{"mix", mix.name},
          {"runs", count},
          {"completed", completed},
          {"max_landing_error_m", cover::bench::figure_json(worst_landing_m)},
          {"max_latency_p99_ms", cover::bench::figure_json(worst_p99_ms)}};
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"Scenario 2 in realtime over a lossy, multicast-free emulated WiFi (root)"};
  bool json = false;
  cover::bench::WifiOptions options;
  app.add_flag("--json", json, "print JSON {rows, summary} instead of a table");
  app.add_option("--seeds", options.seeds, "seeds per vendor mix (1..)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--loss-percent", options.loss_percent, "UDP loss on every link (%)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  app.add_option("--rate", options.rate, "bandwidth cap per namespace (tc tbf rate)")
      ->capture_default_str();
  app.add_option("--domain", options.first_domain, "first DDS domain (10 in turn, one per run)")
      ->check(CLI::Range(0, 222))
      ->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  const cover::bench::WifiResult result =
      cover::bench::run_wifi(options, cover::bench::vendor_mixes(), [&](const WifiRun& run) {
        if (json) return;
        std::printf("%-8s seed %2llu  %-13s landing %s\n", run.row.mix.c_str(),
                    static_cast<unsigned long long>(run.row.seed), run.row.outcome.c_str(),
                    std::isfinite(run.row.landing_error_m)
                        ? std::to_string(run.row.landing_error_m).c_str()
                        : "-");
      });
  if (!result.network_up) {
    std::cerr << "cover-bench wifi: scripts/wifi-sim up failed (root needed):\n"
              << result.network_output;
    return 1;
  }
  std::vector<cover::bench::FaultRow> rows;
  cover::bench::NotMeasured missing;
  for (const WifiRun& run : result.runs) {
    rows.push_back(run.row);
    if (!run.reported) {
      missing.add(run.row.mix + " seed " + std::to_string(run.row.seed) +
                  ": the launch gave no result");
    }
  }
  if (result.runs.empty()) missing.add("no run was flown");
  nlohmann::json summary = nlohmann::json::array();
  for (const VendorMix& mix : cover::bench::vendor_mixes()) {
    summary.push_back(mix_summary(mix, result.runs));
  }
  nlohmann::json out = cover::bench::rows_json(rows);
  out["summary"] = summary;
  out["loss_percent"] = options.loss_percent;
  out["rate"] = options.rate;
  if (json) {
    std::cout << out.dump(2) << "\n";
  } else {
    for (const auto& s : summary) std::printf("%s\n", s.dump().c_str());
  }
  return missing.exit_code("wifi");
}

const cover::bench::Registrar registrar{
    "wifi", "Scenario 2 over emulated lossy WiFi (netns, root): fault rows per vendor mix", &run};

}  // namespace

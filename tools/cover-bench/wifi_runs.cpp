#include "wifi_runs.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cover/process/scoped_setup.hpp"
#include "launch_run.hpp"

namespace cover::bench {

namespace {

#ifdef COVER_WIFI_SIM
constexpr const char* kWifiSim = COVER_WIFI_SIM;
#else
constexpr const char* kWifiSim = "scripts/wifi-sim";
#endif

// A touchdown faster than this is a crash (the bound for a failsafe landing).
constexpr double kSafeTouchdown_m_s = 1.0;

double number_or_nan(const nlohmann::json& j, const char* key) {
  if (j.contains(key) && j[key].is_number()) return j[key].get<double>();
  return std::nan("");
}

// Completed: the mission succeeded. Landed safely: it did not, but the simulator saw a
// touchdown no faster than kSafeTouchdown_m_s. Anything else counts as crashed: a run
// that cannot show it landed softly is not given the benefit of the doubt.
WifiRun run_of(const VendorMix& mix, int seed, const nlohmann::json& r) {
  WifiRun run;
  FaultRow& row = run.row;
  row.fault = "wifi_loss";
  row.mix = mix.name;
  row.seed = static_cast<std::uint64_t>(seed);
  row.time_to_failsafe_ms = number_or_nan(r, "time_to_failsafe_ms");
  row.touchdown_speed_m_s = number_or_nan(r, "touchdown_speed_m_s");
  row.landing_error_m = number_or_nan(r, "landing_error_m");
  row.outcome = "crashed";
  if (r.value("success", false)) {
    row.outcome = "completed";
  } else if (row.touchdown_speed_m_s <= kSafeTouchdown_m_s) {  // false for NaN
    row.outcome = "landed_safely";
  }
  row.detail = r.value("status", std::string());
  run.reported = !r.empty();
  if (r.contains("latency_ms") && r["latency_ms"].is_object()) {
    run.latency_p99_ms = number_or_nan(r["latency_ms"], "p99");
  }
  return run;
}

}  // namespace

WifiResult run_wifi(const WifiOptions& options, const std::vector<VendorMix>& mixes,
                    const std::function<void(const WifiRun&)>& on_run) {
  WifiResult result;
  const auto log = std::filesystem::temp_directory_path() / "cover_wifi_bench_net.log";
  const cover::process::ScopedSetup network(
      {kWifiSim, "up", "--loss-percent", std::to_string(options.loss_percent), "--rate",
       options.rate},
      {kWifiSim, "down"}, log.string());
  result.network_up = network.ok();
  if (!result.network_up) {
    result.network_output = network.up_result().output;
    return result;
  }
  int index = 0;
  for (const VendorMix& mix : mixes) {
    std::vector<std::string> flags = {"--clock", "realtime", "--seed"};
    for (int seed = 1; seed <= options.seeds; ++seed, ++index) {
      std::vector<std::string> run_flags = flags;
      run_flags.push_back(std::to_string(seed));
      const std::vector<std::string> dds = launch_dds_flags(mix);
      run_flags.insert(run_flags.end(), dds.begin(), dds.end());
      const int domain = options.first_domain + index % std::max(options.domain_count, 1);
      result.runs.push_back(
          run_of(mix, seed, run_launch("scenario2_wifi", run_flags, domain, "wifi")));
      if (on_run) on_run(result.runs.back());
    }
  }
  return result;
}

}  // namespace cover::bench

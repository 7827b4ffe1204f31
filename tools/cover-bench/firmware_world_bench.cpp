// cover-bench firmware-world: Scenario 2 flown four ways side by side, each seed through
// cover-launch: our simulated PX4 and ArduPilot (cover-sim --fc) and the real PX4 and
// ArduCopter firmware (SITL) with cover-sim as their physics (cover-sim --firmware). Per way:
// successes, landing error on the moving deck, L_t / L_s, final-stage tracking error,
// lockstep real-time factor; realtime runs add the relative state -> command latency.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/firmware/firmware_build.hpp"
#include "cover/firmware/sitl_ports.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"

namespace {

using cover::bench::figure_json;
using cover::bench::figure_text;

struct Way {
  std::string name;    // "simulated PX4"
  std::string launch;  // config/launch/<launch>.yaml
  bool real = false;   // real firmware: needs its SITL build
  bool px4 = false;
};

const std::vector<Way>& ways() {
  static const std::vector<Way> all = {
      {"simulated PX4", "scenario2_px4", false, true},
      {"real PX4 SITL", "scenario2_px4_sitl", true, true},
      {"simulated ArduPilot", "scenario2_ardupilot", false, false},
      {"real ArduCopter SITL", "scenario2_ardupilot_sitl", true, false},
  };
  return all;
}

double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

// The final stage's tracking error, the norm of its x, y, z.
double tracking_norm(const nlohmann::json& r) {
  if (!r.is_object() || !r.contains("tracking_error_m") || !r["tracking_error_m"].is_array()) {
    return NAN;
  }
  double sum = 0.0;
  for (const auto& e : r["tracking_error_m"]) {
    if (!e.is_number()) return NAN;
    sum += e.get<double>() * e.get<double>();
  }
  return std::sqrt(sum);
}

// Ports and the SITL instance moved per domain, so that a run never meets another's.
std::vector<std::string> port_flags(const Way& way, int domain) {
  const int base = 27000 + 8 * (domain % 100);
  std::vector<std::string> flags;
  auto var = [&](const std::string& name, int value) {
    flags.insert(flags.end(), {"--var", name + "=" + std::to_string(value)});
  };
  if (!way.real) {
    var("fc_port", base);
    var("autopilot_port", base + 1);
    var("ugv0_imu_port", base + 2);
    var("ugv1_imu_port", base + 3);
    var("ugv_autopilot_port", base + 4);
    return flags;
  }
  const int instance = 1 + domain % 8;
  var("instance", instance);
  var("fc_port", cover::firmware::companion_port(instance));
  var("physics_port", cover::firmware::physics_port(
                          way.px4 ? cover::Autopilot::Px4 : cover::Autopilot::ArduPilot, instance));
  return flags;
}

nlohmann::json one_run(const Way& way, const std::string& clock, int seed, int domain) {
  std::vector<std::string> flags = {"--clock", clock, "--seed", std::to_string(seed)};
  for (auto& f : port_flags(way, domain)) flags.push_back(f);
  const nlohmann::json r = cover::bench::run_launch(way.launch, flags, domain, "firmware-world",
                                                    std::chrono::minutes(6));
  const nlohmann::json latency =
      r.is_object() && r.contains("latency_ms") ? r["latency_ms"] : nlohmann::json::object();
  return {{"seed", seed},
          {"clock", clock},
          {"reported", r.is_object() && !r.empty()},
          {"success", r.is_object() && r.value("success", false)},
          {"landing_error_m", figure_json(number(r, "landing_error_m"))},
          {"ratio", figure_json(number(r, "ratio"))},
          {"tracking_error_m", figure_json(tracking_norm(r))},
          {"realtime_factor", figure_json(number(r, "speed_factor"))},
          {"latency_p50_ms", figure_json(number(latency, "p50"))},
          {"latency_p99_ms", figure_json(number(latency, "p99"))}};
}

std::vector<double> figures(const nlohmann::json& runs, const char* key, const std::string& clock) {
  std::vector<double> out;
  for (const auto& r : runs) {
    if (r["clock"] == clock && r[key].is_number()) out.push_back(r[key].get<double>());
  }
  return out;
}

double median_of(const std::vector<double>& v) {
  return v.empty() ? NAN : cover::bench::percentile(v, 0.5);
}
double max_of(const std::vector<double>& v) {
  return v.empty() ? NAN : cover::bench::percentile(v, 1.0);
}

nlohmann::json summarise(const Way& way, const nlohmann::json& runs) {
  int lockstep = 0, lockstep_ok = 0, realtime = 0, realtime_ok = 0;
  for (const auto& r : runs) {
    const bool ok = r["success"].get<bool>();
    (r["clock"] == "lockstep" ? lockstep : realtime) += 1;
    (r["clock"] == "lockstep" ? lockstep_ok : realtime_ok) += ok ? 1 : 0;
  }
  const auto landing = figures(runs, "landing_error_m", "lockstep");
  return {
      {"way", way.name},
      {"launch", way.launch},
      {"lockstep_runs", lockstep},
      {"lockstep_successes", lockstep_ok},
      {"realtime_runs", realtime},
      {"realtime_successes", realtime_ok},
      {"landing_error_median_m", figure_json(median_of(landing))},
      {"landing_error_max_m", figure_json(max_of(landing))},
      {"ratio_median", figure_json(median_of(figures(runs, "ratio", "lockstep")))},
      {"tracking_error_median_m",
       figure_json(median_of(figures(runs, "tracking_error_m", "lockstep")))},
      {"lockstep_realtime_factor_median",
       figure_json(median_of(figures(runs, "realtime_factor", "lockstep")))},
      {"realtime_landing_error_max_m",
       figure_json(max_of(figures(runs, "landing_error_m", "realtime")))},
      {"realtime_latency_p50_ms",
       figure_json(median_of(figures(runs, "latency_p50_ms", "realtime")))},
      {"realtime_latency_p99_ms", figure_json(max_of(figures(runs, "latency_p99_ms", "realtime")))},
      {"runs", runs}};
}

void print_table(const nlohmann::json& rows) {
  std::printf(
      "Scenario 2, our simulated autopilots and the real firmware (lockstep seeds; "
      "realtime runs)\n");
  std::printf("  %-22s %9s %9s %10s %10s %7s %9s %6s %9s %13s\n", "way", "lockstep", "realtime",
              "land med", "land max", "Lt/Ls", "track", "RTF", "rt land", "rt lat p50/99");
  for (const auto& r : rows) {
    auto f = [&](const char* key, const char* format) {
      return figure_text(format, r[key].is_number() ? r[key].get<double>() : NAN);
    };
    const std::string lockstep = std::to_string(r["lockstep_successes"].get<int>()) + "/" +
                                 std::to_string(r["lockstep_runs"].get<int>());
    const std::string realtime = std::to_string(r["realtime_successes"].get<int>()) + "/" +
                                 std::to_string(r["realtime_runs"].get<int>());
    std::printf(
        "  %-22s %9s %9s %10s %10s %7s %9s %6s %9s %6s/%6s\n", r["way"].get<std::string>().c_str(),
        lockstep.c_str(), realtime.c_str(), f("landing_error_median_m", "%.3f m").c_str(),
        f("landing_error_max_m", "%.3f m").c_str(), f("ratio_median", "%.3f").c_str(),
        f("tracking_error_median_m", "%.3f m").c_str(),
        f("lockstep_realtime_factor_median", "%.1f").c_str(),
        f("realtime_landing_error_max_m", "%.3f").c_str(),
        f("realtime_latency_p50_ms", "%.1f").c_str(), f("realtime_latency_p99_ms", "%.1f").c_str());
  }
}

// The real firmware's build, or why it is not measured.
bool firmware_found(const Way& way, cover::bench::NotMeasured& missing) {
  if (!way.real) return true;
  const auto lookup =
      way.px4 ? cover::firmware::find_px4_sitl() : cover::firmware::find_arducopter_sitl();
  if (!lookup.build) missing.add(way.name + ": " + lookup.missing);
  return lookup.build.has_value();
}

void check_rows(const nlohmann::json& row, cover::bench::NotMeasured& missing) {
  for (const auto& r : row["runs"]) {
    if (!r["reported"].get<bool>()) {
      missing.add(row["way"].get<std::string>() + " seed " + std::to_string(r["seed"].get<int>()) +
                  " (" + r["clock"].get<std::string>() + "): the launch gave no result");
    }
  }
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "Scenario 2 through our simulated autopilots and through the real PX4 / "
      "ArduCopter firmware (SITL, COVER_PX4_SITL / COVER_ARDUPILOT_SITL) with cover-sim "
      "as its physics: successes, landing error, L_t/L_s, final tracking error, "
      "lockstep real-time factor; realtime runs add relative state -> command latency"};
  bool json = false;
  int seeds = 10;
  int realtime_runs = 1;
  int domain = 120;
  std::string only;
  app.add_flag("--json", json, "print JSON");
  app.add_option("--seeds", seeds, "lockstep runs per way, seeds 1..N")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--realtime", realtime_runs, "realtime runs per way, seeds 1..N")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--only", only, "px4 or ardupilot: that autopilot's two ways only")
      ->check(CLI::IsMember({"px4", "ardupilot"}));
  app.add_option("--domain", domain, "first DDS domain (one per run)")
      ->check(CLI::Range(0, 200))
      ->capture_default_str();
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;
  if (seeds + realtime_runs == 0) {
    std::cerr << "cover-bench firmware-world: --seeds 0 and --realtime 0 ask for no run\n";
    return 2;
  }

  cover::bench::NotMeasured missing;
  nlohmann::json rows = nlohmann::json::array();
  int next_domain = domain;
  for (const Way& way : ways()) {
    if (!only.empty() && way.px4 != (only == "px4")) continue;
    if (!firmware_found(way, missing)) continue;
    nlohmann::json runs = nlohmann::json::array();
    for (int s = 1; s <= seeds; ++s) runs.push_back(one_run(way, "lockstep", s, next_domain++));
    for (int s = 1; s <= realtime_runs; ++s) {
      runs.push_back(one_run(way, "realtime", s, next_domain++));
    }
    if (!json) std::fprintf(stderr, "firmware-world: %s done\n", way.name.c_str());
    if (next_domain > 230) next_domain = domain;
    rows.push_back(summarise(way, runs));
    check_rows(rows.back(), missing);
  }
  if (json) {
    std::cout << nlohmann::json{{"seeds", seeds}, {"realtime_runs", realtime_runs}, {"ways", rows}}
                     .dump(2)
              << "\n";
  } else {
    print_table(rows);
  }
  return missing.exit_code("firmware-world");
}

const cover::bench::Registrar registrar{
    "firmware-world",
    "Scenario 2 through our simulated autopilots and the real PX4 / ArduCopter firmware with "
    "cover-sim as its physics: success, landing, L_t/L_s, tracking, real-time factor",
    &run};

}  // namespace

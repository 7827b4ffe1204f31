// cover-bench fleet: what each vehicle costs as the fleet grows. config/launch/fleet16.yaml
// flown (lockstep by default) with 1, 2, 4, 8, 16 UAVs, each over its pair of UGVs
// (--var uavs=N --var ugvs=max(N, 2)): the CPU time of each process per simulated second
// and per wall second (UAV agents, UGV agents, the simulator, the task manager; the sum),
// each process's peak memory, the real-time factor, the agents' samples the simulator
// received a wall second, the relative state -> command latency (realtime), the host's
// load average, and whether every task succeeded with its landing error. --svg writes the
// cost against fleet size as a plot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/dds/domain_claim.hpp"
#include "launch_run.hpp"
#include "not_measured.hpp"

namespace {

using nlohmann::json;

// One role's processes in one run: CPU per simulated second and peak memory.
struct RoleCost {
  int processes = 0;
  double cpu_s = 0.0;        // summed
  double max_rss_mib = 0.0;  // the largest of them
};

struct FleetRow {
  int uavs = 0;
  int ugvs = 0;
  bool success = false;
  double sim_s = 0.0;
  double speed_factor = 0.0;  // simulated s per wall s
  double worst_landing_m = 0.0;
  double samples_per_wall_s = -1.0;  // agents' commands and traces into the simulator
  double latency_p50_ms = -1.0, latency_p99_ms = -1.0;  // realtime only
  double load_average = -1.0;                           // 1 min, at the run's end
  RoleCost uav, ugv, sim, manager;
  double wall_s() const { return speed_factor > 0.0 ? sim_s / speed_factor : 0.0; }
};

// The host's 1-minute load average: other work on the same cores skews every figure.
double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = -1.0;
  in >> one;
  return one;
}

std::string role_of(const std::string& name) {
  if (name.rfind("uav", 0) == 0) return "uav";
  if (name.rfind("ugv", 0) == 0) return "ugv";
  return name;
}

bool read_row(const json& report, FleetRow& row) {
  if (!report.is_object() || !report.contains("processes")) return false;
  row.success = report.value("success", false);
  row.speed_factor = report.value("speed_factor", 0.0);
  if (report.contains("agent_samples")) {
    row.samples_per_wall_s = report["agent_samples"].value("per_wall_s", -1.0);
  }
  if (report.contains("latency_ms")) {
    row.latency_p50_ms = report["latency_ms"].value("p50", -1.0);
    row.latency_p99_ms = report["latency_ms"].value("p99", -1.0);
  }
  const json& uavs = report.contains("uavs") ? report["uavs"] : json::array({report});
  for (const json& u : uavs) {
    row.sim_s = std::max(row.sim_s, u.value("duration_s", 0.0));
    const json& landing = u["landing_error_m"];
    if (landing.is_number())
      row.worst_landing_m = std::max(row.worst_landing_m, landing.get<double>());
  }
  for (const json& p : report["processes"]) {
    if (!p["cpu_s"].is_number()) continue;
    const std::string role = role_of(p.value("name", ""));
    RoleCost* cost = role == "uav"            ? &row.uav
                     : role == "ugv"          ? &row.ugv
                     : role == "sim"          ? &row.sim
                     : role == "task_manager" ? &row.manager
                                              : nullptr;
    if (cost == nullptr) continue;
    ++cost->processes;
    cost->cpu_s += p["cpu_s"].get<double>();
    if (p["max_rss_kib"].is_number()) {
      cost->max_rss_mib = std::max(cost->max_rss_mib, p["max_rss_kib"].get<double>() / 1024.0);
    }
  }
  return row.sim_s > 0.0 && row.uav.processes == row.uavs && row.ugv.processes == row.ugvs &&
         row.sim.processes == 1 && row.manager.processes == 1;
}

// CPU seconds per simulated second of one process of the role (its share of a core at
// real time).
double per_process(const RoleCost& cost, double sim_s) {
  return cost.processes > 0 ? cost.cpu_s / cost.processes / sim_s : 0.0;
}

double total_cpu_s(const FleetRow& r) {
  return r.uav.cpu_s + r.ugv.cpu_s + r.sim.cpu_s + r.manager.cpu_s;
}

json row_json(const FleetRow& r) {
  const auto role = [&](const RoleCost& c) {
    return json{{"processes", c.processes},
                {"cpu_per_process_per_sim_s", per_process(c, r.sim_s)},
                {"cpu_per_process_per_wall_s", per_process(c, r.wall_s())},
                {"cpu_total_per_sim_s", c.cpu_s / r.sim_s},
                {"max_rss_mib", c.max_rss_mib}};
  };
  const auto or_null = [](double v) { return v >= 0.0 ? json(v) : json(nullptr); };
  return {{"uavs", r.uavs},
          {"ugvs", r.ugvs},
          {"success", r.success},
          {"simulated_s", r.sim_s},
          {"realtime_factor", r.speed_factor},
          {"wall_s", r.wall_s()},
          {"worst_landing_error_m", r.worst_landing_m},
          {"cpu_total_per_sim_s", total_cpu_s(r) / r.sim_s},
          {"cpu_total_per_wall_s", total_cpu_s(r) / r.wall_s()},
          {"agent_samples_per_wall_s", or_null(r.samples_per_wall_s)},
          {"latency_p50_ms", or_null(r.latency_p50_ms)},
          {"latency_p99_ms", or_null(r.latency_p99_ms)},
          {"load_average", or_null(r.load_average)},
          {"uav_agent", role(r.uav)},
          {"ugv_agent", role(r.ugv)},
          {"simulator", role(r.sim)},
          {"task_manager", role(r.manager)}};
}

// Cost against fleet size: one polyline per series, x = UAVs (log2 spacing), y = CPU
// seconds per simulated second.
std::string svg_plot(const std::vector<FleetRow>& rows, const std::string& clock) {
  struct Series {
    std::string name, colour;
    double (*value)(const FleetRow&);
  };
  const std::vector<Series> series{
      {"UAV agent (each)", "#1f77b4",
       [](const FleetRow& r) { return per_process(r.uav, r.sim_s); }},
      {"UGV agent (each)", "#2ca02c",
       [](const FleetRow& r) { return per_process(r.ugv, r.sim_s); }},
      {"simulator", "#d62728", [](const FleetRow& r) { return r.sim.cpu_s / r.sim_s; }},
      {"task manager", "#ff7f0e", [](const FleetRow& r) { return r.manager.cpu_s / r.sim_s; }},
      {"whole fleet / N", "#9467bd",
       [](const FleetRow& r) { return total_cpu_s(r) / r.sim_s / r.uavs; }}};
  double y_max = 0.0;
  for (const auto& s : series)
    for (const auto& r : rows) y_max = std::max(y_max, s.value(r));
  y_max = std::max(1e-3, y_max * 1.1);
  const double x_max = std::log2(std::max(2, rows.back().uavs));
  const int w = 720, h = 420, left = 70, right = 190, top = 40, bottom = 50;
  const auto px = [&](int uavs) { return left + (w - left - right) * std::log2(uavs) / x_max; };
  const auto py = [&](double v) { return top + (h - top - bottom) * (1.0 - v / y_max); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n<text x=\""
      << left << "\" y=\"22\" font-size=\"14\">cover-bench fleet: CPU s per simulated s "
      << "against fleet size (" << clock << ")</text>\n";
  svg << "<line x1=\"" << left << "\" y1=\"" << py(0) << "\" x2=\"" << w - right << "\" y2=\""
      << py(0) << "\" stroke=\"black\"/>\n<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\""
      << left << "\" y2=\"" << py(0) << "\" stroke=\"black\"/>\n";
  for (int i = 0; i <= 4; ++i) {
    const double v = y_max * i / 4;
    svg << "<text x=\"" << left - 6 << "\" y=\"" << py(v) + 4 << "\" text-anchor=\"end\">"
        << std::fixed << std::setprecision(3) << v << "</text>\n";
  }
  for (const auto& r : rows) {
    svg << "<text x=\"" << px(r.uavs) << "\" y=\"" << h - bottom + 18
        << "\" text-anchor=\"middle\">" << r.uavs << "</text>\n";
  }
  svg << "<text x=\"" << (left + w - right) / 2 << "\" y=\"" << h - 12
      << "\" text-anchor=\"middle\">UAVs (each over its pair of UGVs)</text>\n";
  int legend_y = top + 10;
  for (const auto& s : series) {
    svg << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << s.colour << "\" points=\"";
    for (const auto& r : rows) svg << px(r.uavs) << "," << py(s.value(r)) << " ";
    svg << "\"/>\n";
    for (const auto& r : rows) {
      svg << "<circle r=\"3\" fill=\"" << s.colour << "\" cx=\"" << px(r.uavs) << "\" cy=\""
          << py(s.value(r)) << "\"/>\n";
    }
    svg << "<line x1=\"" << w - right + 12 << "\" y1=\"" << legend_y << "\" x2=\"" << w - right + 32
        << "\" y2=\"" << legend_y << "\" stroke-width=\"2\" stroke=\"" << s.colour
        << "\"/><text x=\"" << w - right + 38 << "\" y=\"" << legend_y + 4 << "\">" << s.name
        << "</text>\n";
    legend_y += 20;
  }
  svg << "</svg>\n";
  return svg.str();
}

void print_table(const std::vector<FleetRow>& rows) {
  std::printf(
      "%4s %4s %3s %6s %8s %8s %8s %8s %8s | %8s %8s %8s %8s | %5s %5s %5s %5s %8s %7s "
      "%7s %6s %5s\n",
      "UAVs", "UGVs", "ok", "RTF", "uav", "ugv", "sim", "tm", "total/N", "uav/w", "ugv/w", "sim/w",
      "tm/w", "uavM", "ugvM", "simM", "tmM", "smp/s", "p50ms", "p99ms", "landcm", "load");
  for (const auto& r : rows) {
    const double w = r.wall_s();
    std::printf(
        "%4d %4d %3s %6.2f %8.4f %8.4f %8.4f %8.4f %8.4f | %8.4f %8.4f %8.4f %8.4f | %5.1f "
        "%5.1f %5.1f %5.1f %8.0f %7.2f %7.2f %6.2f %5.1f\n",
        r.uavs, r.ugvs, r.success ? "yes" : "NO", r.speed_factor, per_process(r.uav, r.sim_s),
        per_process(r.ugv, r.sim_s), r.sim.cpu_s / r.sim_s, r.manager.cpu_s / r.sim_s,
        total_cpu_s(r) / r.sim_s / r.uavs, per_process(r.uav, w), per_process(r.ugv, w),
        r.sim.cpu_s / w, r.manager.cpu_s / w, r.uav.max_rss_mib, r.ugv.max_rss_mib,
        r.sim.max_rss_mib, r.manager.max_rss_mib, r.samples_per_wall_s, r.latency_p50_ms,
        r.latency_p99_ms, 100.0 * r.worst_landing_m, r.load_average);
  }
  std::printf(
      "(CPU seconds per simulated second (left) and per wall second (/w), per process of the "
      "role; total/N: the whole fleet's per UAV; M: peak RSS MiB; smp/s: agents' samples into "
      "the simulator per wall second; p50/p99: relative state -> command latency, realtime; "
      "load: 1-min load average at the run's end)\n");
}

int run(const std::vector<std::string>& args) {
  CLI::App app{
      "cover-bench fleet: cost per vehicle against fleet size (config/launch/fleet16.yaml)"};
  std::vector<int> sizes{1, 2, 4, 8, 16};
  std::string clock = "lockstep";
  std::string dds = "fastdds";
  std::string svg_file;
  bool as_json = false;
  app.add_option("--uavs", sizes, "fleet sizes (UAVs; UGVs = max(UAVs, 2))")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--clock", clock)
      ->check(CLI::IsMember({"lockstep", "realtime"}))
      ->capture_default_str();
  app.add_option("--dds", dds, "every process on fastdds|cyclone")
      ->check(CLI::IsMember({"fastdds", "cyclone"}));
  app.add_option("--svg", svg_file, "write the plot of cost against fleet size here");
  app.add_flag("--json", as_json);
  if (const int code = cover::bench::parse_args(app, args); code >= 0) return code;
  for (const int n : sizes) {
    if (n < 1 || n > 32 || (n > 1 && n % 2 != 0)) {
      std::cerr << "cover-bench fleet: --uavs " << n << ": 1 or an even number up to 32\n";
      return 2;
    }
  }
  std::vector<FleetRow> rows;
  cover::bench::NotMeasured missing;
  for (const int n : sizes) {
    FleetRow row;
    row.uavs = n;
    row.ugvs = std::max(n, 2);
    const auto claim = cover::dds::DomainClaim::claim_any(150, 220);
    const json report = cover::bench::run_launch(
        "fleet16",
        {"--clock", clock, "--dds", "*=" + dds, "--var", "uavs=" + std::to_string(row.uavs),
         "--var", "ugvs=" + std::to_string(row.ugvs)},
        claim.domain(), "fleet", std::chrono::minutes(20));
    row.load_average = load_average();
    if (!read_row(report, row)) {
      missing.add(std::to_string(n) + " UAVs: the launch gave no complete report");
      continue;
    }
    std::cerr << "cover-bench fleet: " << n << " UAV(s) done, RTF " << row.speed_factor << "\n";
    rows.push_back(row);
  }
  if (!rows.empty() && !svg_file.empty()) {
    const std::filesystem::path svg_path(svg_file);
    if (svg_path.has_parent_path()) std::filesystem::create_directories(svg_path.parent_path());
    std::ofstream svg(svg_path);
    svg << svg_plot(rows, clock);
    if (!svg) {
      std::cerr << "cover-bench fleet: cannot write " << svg_file << "\n";
      return 2;
    }
  }
  const bool all_succeeded =
      std::all_of(rows.begin(), rows.end(), [](const FleetRow& r) { return r.success; });
  if (as_json) {
    json out = json::array();
    for (const auto& r : rows) out.push_back(row_json(r));
    std::cout << json{{"clock", clock}, {"dds", dds}, {"rows", out}}.dump(2) << "\n";
  } else {
    print_table(rows);
  }
  return missing.exit_code("fleet", all_succeeded ? 0 : 1);
}

const cover::bench::Registrar kRegistrar{
    "fleet", "cost per UAV / UGV agent and simulator, memory, RTF for 1..16 UAVs (fleet16.yaml)",
    &run};

}  // namespace

// cover-bench table1: the paper's Table 1. The UAV transits cyclically G0 <-> G1 while both
// UGVs drive circles; for each (v, w) and method it reports the world-frame transition path
// length L_t, the straight-line length L_s and their ratio (1 = no detour).
//
// One long cyclic run locks into a few relative geometries (its period against the UGVs'
// turn), and each method into different ones, since their stages last differently: over
// 20 transitions cover's (0.8, 0.35) ratio ranges from 1.17 to 1.30 across planner
// settings whose plans hardly differ. So each cell is `--phases` short cyclic runs
// (default 12 x there-and-back) with G1 starting a further 1/phases of a turn each time:
// every method starts its first transitions from the same, evenly spread geometries, and
// cover's ratios agree within 0.001 between 12 and 24 phases.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/model/angles.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"

namespace {

// One (v, w, method) cell of the table, summed over the runs (one per starting phase).
struct Row {
  double v = 0.0;
  double w = 0.0;
  std::string method;
  int requested = 0;  // transition processes asked for, over all runs
  std::vector<cover::sim::TransitionRecord> transitions;
  std::vector<int> run_of_transition;  // which run (phase) each transition belongs to
  std::vector<std::string> statuses;   // one per run
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;

  void add_run(const cover::sim::ClosedLoopResult& result, int requested_in_run) {
    const int run = static_cast<int>(statuses.size());
    for (const auto& t : result.transitions) {
      transitions.push_back(t);
      run_of_transition.push_back(run);
    }
    statuses.push_back(result.status);
    requested += requested_in_run;
    sim_time_s += result.realtime_factor * result.wall_time_s;
    wall_time_s += result.wall_time_s;
  }
  int completed() const {
    int n = 0;
    for (const auto& t : transitions) n += t.completed ? 1 : 0;
    return n;
  }
  // Sums over the completed transitions of `length(record)`.
  template <typename Length>
  double sum(Length length) const {
    double total = 0.0;
    for (const auto& t : transitions) total += t.completed ? length(t) : 0.0;
    return total;
  }
  double Ls() const {
    return sum([](const auto& t) { return t.straight_length_m; });
  }
  double Lt() const {
    return sum([](const auto& t) { return t.path_length_m; });
  }
  double ratio() const { return Ls() > 0.0 ? Lt() / Ls() : std::nan(""); }
  // What the eq. 30 law would reach from the same starts with a perfect controller.
  double eq30_law_ratio() const {
    const double ls = sum([](const auto& t) { return t.eq30_law.straight_length_m; });
    const double lt = sum([](const auto& t) { return t.eq30_law.path_length_m; });
    return ls > 0.0 ? lt / ls : std::nan("");
  }
  double realtime_factor() const { return wall_time_s > 0.0 ? sim_time_s / wall_time_s : 0.0; }
};

// Table 1's world with both UGVs on circles of speed v and turn rate w; a positive
// `separation_m` moves the two circle centres that far apart (symmetric about the origin);
// G1 starts `phase_offset_rad` further round its circle than the scenario file says.
cover::sim::Scenario table1_scenario(double v, double w, int transitions, double separation_m,
                                     double phase_offset_rad) {
  cover::sim::Scenario scenario =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("table1"));
  for (auto& ugv : scenario.world.ugvs) {
    ugv.pattern.speed_m_s = v;
    ugv.pattern.yaw_rate_rad_s = w;
  }
  if (separation_m > 0.0 && scenario.world.ugvs.size() == 2) {
    scenario.world.ugvs[0].pattern.origin_m = {-0.5 * separation_m, 0.0};
    scenario.world.ugvs[1].pattern.origin_m = {0.5 * separation_m, 0.0};
  }
  if (scenario.world.ugvs.size() == 2) scenario.world.ugvs[1].pattern.phase_rad += phase_offset_rad;
  scenario.task = cover::mission::repeat_processes(scenario.task, transitions);
  // Each process (take-off height, transit, descend) takes well under a minute.
  scenario.max_duration_s = 60.0 * transitions;
  scenario.validate();
  return scenario;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("Table 1: cyclic G0 <-> G1 transitions, world-frame transition paths\n");
  std::printf("%6s %6s  %-11s %9s %9s %8s %9s %12s %9s\n", "v m/s", "w r/s", "method", "Ls m",
              "Lt m", "Lt/Ls", "eq30 law", "transitions", "failures");
  for (const Row& r : rows) {
    std::printf("%6.2f %6.2f  %-11s %9.2f %9.2f %8.3f %9.3f %7d / %-4d %9d\n", r.v, r.w,
                r.method.c_str(), r.Ls(), r.Lt(), r.ratio(), r.eq30_law_ratio(), r.completed(),
                r.requested, r.requested - r.completed());
  }
  std::printf(
      "Lt/Ls = 1 is the straight line; the paper reports < 1.1 for COVER and a detour\n"
      "growing with w for CoNi-MPC. \"eq30 law\": Lt/Ls of a point mass that flies the\n"
      "paper's velocity law (eq. 30) perfectly from the same transition starts: the UAV\n"
      "moves with the target UGV plus the approach, so the UGV's curve is in its path.\n");
}

// What the command line asks for.
struct Options {
  bool json = false;
  int transitions = 2;
  int phases = 12;
  std::optional<std::uint64_t> seed;  // none: the scenario file's
  std::vector<std::string> methods;
  double separation_m = 0.0;
  bool plot = false;
  std::string plot_file;
  std::vector<std::pair<double, double>> settings;  // (v, w)
};

// Fills `options`; returns -1 to go on, or the exit code (after --help or a usage error).
int parse_options(const std::vector<std::string>& args, Options& options) {
  CLI::App app{"Table 1: cyclic transitions between two circling UGVs (L_t / L_s)"};
  double v = 0.0;
  double w = 0.0;
  std::uint64_t seed = 0;
  app.add_flag("--json", options.json, "print JSON instead of a table");
  auto* v_opt = app.add_option("--v", v, "UGV speed, m/s (with --w; default: the paper's three)");
  auto* w_opt = app.add_option("--w", w, "UGV turn rate, rad/s");
  app.add_option("--transitions", options.transitions,
                 "transition processes per run (default 2: there and back)")
      ->check(CLI::Range(1, 100));
  app.add_option("--phases", options.phases,
                 "runs per cell, G1 starting 1/phases of a turn further each time (default 12)")
      ->check(CLI::Range(1, 36));
  app.add_option("--seed", seed, "world seed (default: the scenario file's)");
  for (const cover::sampc::Mode mode : cover::bench::baseline_first_modes())
    options.methods.emplace_back(cover::sampc::to_string(mode));
  app.add_option("--method", options.methods, "methods to run (default: all three)")
      ->check(CLI::IsMember(cover::bench::method_names()));
  app.add_option("--separation-m", options.separation_m,
                 "distance between the two circle centres, m (default: the scenario file's, 5)")
      ->check(CLI::Range(0.5, 50.0));
  CLI::Option* plot = app.add_option(
      "--plot", options.plot_file,
      "SVG of the first setting's cover run (default table1.svg); baselines get _<method>");
  plot->expected(0, 1);
  v_opt->needs(w_opt);
  w_opt->needs(v_opt);
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  if (app.count("--seed") > 0) options.seed = seed;
  options.settings = {{0.5, 0.25}, {0.5, 0.35}, {0.8, 0.35}};
  if (v_opt->count() > 0) options.settings = {{v, w}};
  options.plot = plot->count() > 0;
  if (options.plot && options.plot_file.empty()) options.plot_file = "table1.svg";
  return -1;
}

// The run's plot: cover's under the given name, the baselines' with _<method>.
bool write_plot(const Options& options, const Row& row, cover::sampc::Mode mode,
                const cover::sim::ClosedLoopResult& result, const cover::sim::Scenario& scenario) {
  const std::string file = mode == cover::sampc::Mode::Cover
                               ? options.plot_file
                               : cover::sim::with_suffix(options.plot_file, row.method);
  char title[160];
  std::snprintf(title, sizeof(title), "Table 1, v = %.2f m/s, w = %.2f rad/s: %s", row.v, row.w,
                row.method.c_str());
  if (cover::sim::write_path_plot(result, scenario, title, file)) return true;
  std::cerr << "cannot write " << file << "\n";
  return false;
}

// One cell: `options.phases` runs of one setting and method. The first setting's first run
// is plotted when asked. False when the plot cannot be written.
bool run_cell(const Options& options, std::size_t setting, Row& row) {
  const cover::sampc::Mode mode = *cover::sampc::parse_mode(row.method);
  const auto config = cover::uav::ControllerConfig::load_default(mode);
  // A cyclic run tends to lock into a few geometries (its period against the UGVs' turn);
  // runs from spread starting phases sample the relative positions more evenly.
  for (int phase = 0; phase < options.phases; ++phase) {
    cover::sim::Scenario scenario =
        table1_scenario(row.v, row.w, options.transitions, options.separation_m,
                        cover::model::kTwoPi * phase / options.phases);
    if (options.seed) scenario.world.seed = *options.seed;
    cover::sim::ClosedLoopOptions loop_options;
    loop_options.record_paths = options.plot && setting == 0 && phase == 0;
    const cover::sim::ClosedLoop loop(scenario, config, loop_options);
    const cover::sim::ClosedLoopResult result = loop.run();
    row.add_run(result, options.transitions);
    if (loop_options.record_paths && !write_plot(options, row, mode, result, scenario)) {
      return false;
    }
  }
  return true;
}

// Per transition, to see which geometry bends the path.
nlohmann::json transitions_json(const Row& r) {
  nlohmann::json stages = nlohmann::json::array();
  for (std::size_t i = 0; i < r.transitions.size(); ++i) {
    const cover::sim::TransitionRecord& t = r.transitions[i];
    stages.push_back({{"run", r.run_of_transition[i]},
                      {"from", t.from_ugv},
                      {"to", t.to_ugv},
                      {"completed", t.completed},
                      {"start_s", t.start_time_s},
                      {"duration_s", t.end_time_s - t.start_time_s},
                      {"Ls", t.straight_length_m},
                      {"Lt", t.path_length_m},
                      {"eq30_law_Ls", t.eq30_law.straight_length_m},
                      {"eq30_law_Lt", t.eq30_law.path_length_m},
                      {"eq30_law_duration_s", t.eq30_law.duration_s}});
  }
  return stages;
}

nlohmann::json table_json(const Options& options, const std::vector<Row>& rows) {
  nlohmann::json out;
  out["transitions_per_run"] = options.transitions;
  out["runs_per_row"] = options.phases;
  out["rows"] = nlohmann::json::array();
  for (const Row& r : rows) {
    out["rows"].push_back({{"v", r.v},
                           {"w", r.w},
                           {"method", r.method},
                           {"Ls", r.Ls()},
                           {"Lt", r.Lt()},
                           {"ratio", cover::sim::number_or_null(r.ratio())},
                           {"eq30_law_ratio", cover::sim::number_or_null(r.eq30_law_ratio())},
                           {"transitions", r.completed()},
                           {"failures", r.requested - r.completed()},
                           {"statuses", r.statuses},
                           {"realtime_factor", r.realtime_factor()},
                           {"per_transition", transitions_json(r)}});
  }
  if (options.plot) out["plot"] = options.plot_file;
  return out;
}

int run(const std::vector<std::string>& args) {
  Options options;
  if (int rc = parse_options(args, options); rc >= 0) return rc;

  std::vector<Row> rows;
  for (std::size_t s = 0; s < options.settings.size(); ++s) {
    for (const std::string& method : options.methods) {
      Row row{options.settings[s].first, options.settings[s].second, method};
      if (!run_cell(options, s, row)) return 1;
      rows.push_back(std::move(row));
    }
  }

  if (options.json) {
    std::cout << table_json(options, rows).dump(2) << "\n";
  } else {
    print_table(rows);
    if (options.plot) std::printf("plot: %s (baselines: _<method>)\n", options.plot_file.c_str());
  }
  return 0;
}

const cover::bench::Registrar registrar{"table1", "paper Table 1: transition path ratio Lt/Ls",
                                        &run};

}  // namespace

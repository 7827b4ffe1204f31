// cover-bench table1: the paper's Table 1. The UAV transits cyclically G0 -> G1 -> G0 while
// both UGVs drive circles; for each (v, w) and method it reports the world-frame transition
// path length L_t, the straight-line length L_s and their ratio (1 = no detour), beside what
// the eq. 30 law would fly from the same starts and the shortest path physically possible
// within the task's limits (the bound).
//
// The paper flies long cyclic runs, whose transitions start from every relative geometry.
// One long simulated run locks into a few geometries instead (its period beats against the
// UGVs' turn, differently for each method). So each cell is `--runs` short cyclic runs, each
// starting both UGVs at phases drawn uniformly from a seeded generator (`--sample-seed`):
// every method flies the same draws, and the cell averages over the geometries as a long
// run of the paper does. `--sampling stepped` keeps the former design: G0 always at the
// scenario file's phase, G1 a further 1/phases of a turn each run.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"
#include "cover/sim/transition_plot.hpp"
#include "cover/vocabulary/angles.hpp"
#include "not_measured.hpp"

namespace {

// Where both UGVs start one run: their circles' phases, rad.
struct RunStart {
  double g0_phase_rad = 0.0;
  double g1_phase_rad = 0.0;
};

// Sum of L_t over sum of L_s; NaN without any.
double ratio_of(double lt, double ls) {
  return ls > 0.0 ? lt / ls : std::nan("");
}

// One (v, w, method) cell of the table, summed over its runs.
struct Row {
  double v = 0.0;
  double w = 0.0;
  std::string method;
  int requested = 0;  // transition processes asked for, over all runs
  std::vector<cover::sim::TransitionRecord> transitions;
  std::vector<int> run_of_transition;  // which run each transition belongs to
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
  // Completed transitions whose bound found no arrival within the budget (the flight
  // broke the limits the bound assumes); they are left out of bound_ratio.
  int bound_unreached() const {
    int n = 0;
    for (const auto& t : transitions) n += t.completed && !t.bound.reached ? 1 : 0;
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
  double ratio() const { return ratio_of(Lt(), Ls()); }
  // L_s and L_t, NaN (not measured) when no transition completed.
  double measured_Ls() const { return completed() > 0 ? Ls() : std::nan(""); }
  double measured_Lt() const { return completed() > 0 ? Lt() : std::nan(""); }
  // What the eq. 30 law would reach from the same starts with a perfect controller.
  double eq30_law_ratio() const {
    return ratio_of(sum([](const auto& t) { return t.eq30_law.path_length_m; }),
                    sum([](const auto& t) { return t.eq30_law.straight_length_m; }));
  }
  // The shortest paths within the limits from the same starts.
  double bound_ratio() const {
    return ratio_of(
        sum([](const auto& t) { return t.bound.reached ? t.bound.path_length_m : 0.0; }),
        sum([](const auto& t) { return t.bound.reached ? t.bound.straight_length_m : 0.0; }));
  }
  double realtime_factor() const { return wall_time_s > 0.0 ? sim_time_s / wall_time_s : 0.0; }
};

// What the command line asks for.
struct Options {
  bool json = false;
  int transitions = 2;
  std::string sampling = "uniform";
  int runs = 400;
  std::uint64_t sample_seed = 1;
  int phases = 12;
  std::optional<std::uint64_t> seed;  // none: the scenario file's
  std::vector<std::string> methods;
  double separation_m = 0.0;
  bool plot = false;
  std::string plot_file;
  std::string transitions_plot_file;                // empty: none
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
  app.add_option("--sampling", options.sampling,
                 "starting phases: uniform (both UGVs drawn at random, default) | stepped "
                 "(G0 fixed, G1 1/phases of a turn further each run)")
      ->check(CLI::IsMember({"uniform", "stepped"}));
  app.add_option("--runs", options.runs, "uniform sampling: runs per cell (default 400)")
      ->check(CLI::Range(1, 10000));
  app.add_option("--sample-seed", options.sample_seed,
                 "uniform sampling: seed of the phase draws (default 1)");
  app.add_option("--phases", options.phases, "stepped sampling: runs per cell (default 12)")
      ->check(CLI::Range(1, 36));
  app.add_option("--seed", seed, "world seed (default: the scenario file's)");
  for (const cover::sampc::Mode mode : cover::bench::baseline_first_modes())
    options.methods.emplace_back(cover::sampc::to_string(mode));
  app.add_option("--method", options.methods, "methods to run (default: every one)")
      ->check(CLI::IsMember(cover::bench::method_names()));
  app.add_option("--separation-m", options.separation_m,
                 "distance between the two circle centres, m (default: the scenario file's, 5)")
      ->check(CLI::Range(0.5, 50.0));
  CLI::Option* plot = app.add_option(
      "--plot", options.plot_file,
      "SVG of the first setting's first run per method (default table1.svg: cover; the "
      "others _<method>)");
  plot->expected(0, 1);
  app.add_option("--plot-transitions", options.transitions_plot_file,
                 "SVG of the first setting's first transition, one per method, from the same "
                 "starting phases (Fig. 7b-like)");
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

// Table 1's world with both UGVs on circles of speed v and turn rate w from `start`; a
// positive `separation_m` moves the two circle centres that far apart (symmetric about
// the origin).
cover::sim::Scenario table1_scenario(const Options& options, double v, double w,
                                     const RunStart& start) {
  cover::sim::Scenario scenario =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("table1"));
  for (auto& ugv : scenario.world.ugvs) {
    ugv.pattern.speed_m_s = v;
    ugv.pattern.yaw_rate_rad_s = w;
  }
  if (scenario.world.ugvs.size() == 2) {
    if (options.separation_m > 0.0) {
      scenario.world.ugvs[0].pattern.origin_m = {-0.5 * options.separation_m, 0.0};
      scenario.world.ugvs[1].pattern.origin_m = {0.5 * options.separation_m, 0.0};
    }
    scenario.world.ugvs[0].pattern.phase_rad = start.g0_phase_rad;
    scenario.world.ugvs[1].pattern.phase_rad = start.g1_phase_rad;
  }
  if (options.seed) scenario.world.seed = *options.seed;
  scenario.task = cover::mission::repeat_processes(scenario.task, options.transitions);
  // Each process (take-off height, transit, descend) takes well under a minute.
  scenario.max_duration_s = 60.0 * options.transitions;
  scenario.validate();
  return scenario;
}

// Every cell's runs start from these phases, the same for every method and setting.
std::vector<RunStart> run_starts(const Options& options) {
  const cover::sim::Scenario file =
      cover::sim::Scenario::load_file(cover::sim::scenario_path("table1"));
  const double g0 = file.world.ugvs.at(0).pattern.phase_rad;
  const double g1 = file.world.ugvs.at(1).pattern.phase_rad;
  std::vector<RunStart> starts;
  if (options.sampling == "stepped") {
    for (int i = 0; i < options.phases; ++i)
      starts.push_back({g0, g1 + cover::model::kTwoPi * i / options.phases});
    return starts;
  }
  std::mt19937_64 generator(options.sample_seed);
  std::uniform_real_distribution<double> phase(0.0, cover::model::kTwoPi);
  for (int i = 0; i < options.runs; ++i) {
    const double a = phase(generator);
    starts.push_back({a, phase(generator)});
  }
  return starts;
}

std::string setting_title(const char* what, const Row& row) {
  char title[160];
  std::snprintf(title, sizeof(title), "Table 1, v = %.2f m/s, w = %.2f rad/s: %s", row.v, row.w,
                what);
  return title;
}

// The run's plot: cover's under the given name, the other methods' with _<method>.
bool write_run_plot(const Options& options, const Row& row,
                    const cover::sim::ClosedLoopResult& result,
                    const cover::sim::Scenario& scenario) {
  const std::string file = row.method == cover::sampc::to_string(cover::sampc::Mode::Cover)
                               ? options.plot_file
                               : cover::sim::with_suffix(options.plot_file, row.method);
  if (cover::sim::write_path_plot(result, scenario, setting_title(row.method.c_str(), row), file))
    return true;
  std::cerr << "cannot write " << file << "\n";
  return false;
}

// One cell: every run of one setting and method. The first setting's first run keeps its
// paths when a plot is asked for (`first_transition` gets its first transition).
bool run_cell(const Options& options, std::size_t setting, const std::vector<RunStart>& starts,
              Row& row, cover::sim::TransitionTrace& first_transition) {
  const auto config =
      cover::uav::ControllerConfig::load_default(*cover::sampc::parse_mode(row.method));
  for (std::size_t run = 0; run < starts.size(); ++run) {
    const cover::sim::Scenario scenario = table1_scenario(options, row.v, row.w, starts[run]);
    cover::sim::ClosedLoopOptions loop_options;
    const bool first = setting == 0 && run == 0;
    loop_options.record_paths = first && (options.plot || !options.transitions_plot_file.empty());
    const cover::sim::ClosedLoopResult result =
        cover::sim::ClosedLoop(scenario, config, loop_options).run();
    row.add_run(result, options.transitions);
    if (!loop_options.record_paths) continue;
    first_transition = cover::sim::transition_trace(result, 0, row.method);
    if (options.plot && !write_run_plot(options, row, result, scenario)) return false;
  }
  return true;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("Table 1: cyclic G0 -> G1 -> G0 transitions, world-frame transition paths\n");
  std::printf("%6s %6s  %-11s %9s %9s %8s %9s %7s %12s %9s\n", "v m/s", "w r/s", "method", "Ls m",
              "Lt m", "Lt/Ls", "eq30 law", "bound", "transitions", "failures");
  for (const Row& r : rows) {
    using cover::bench::figure_text;
    std::printf(
        "%6.2f %6.2f  %-11s %9s %9s %8s %9s %7s %7d / %-4d %9d\n", r.v, r.w, r.method.c_str(),
        figure_text("%.2f", r.measured_Ls()).c_str(), figure_text("%.2f", r.measured_Lt()).c_str(),
        figure_text("%.3f", r.ratio()).c_str(), figure_text("%.3f", r.eq30_law_ratio()).c_str(),
        figure_text("%.3f", r.bound_ratio()).c_str(), r.completed(), r.requested,
        r.requested - r.completed());
  }
  std::printf(
      "Lt/Ls = 1 is the straight line; the paper reports < 1.1 for COVER and a detour\n"
      "growing with w for CoNi-MPC. \"eq30 law\": Lt/Ls of a point mass that flies the\n"
      "paper's velocity law (eq. 30) perfectly from the same transition starts. \"bound\":\n"
      "the shortest paths within the task's speed and acceleration limits from the same\n"
      "starts, arriving by each transition's own end: no flight within the limits is shorter.\n");
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
                      {"eq30_law_duration_s", t.eq30_law.duration_s},
                      {"bound_reached", t.bound.reached},
                      {"bound_Ls", t.bound.straight_length_m},
                      {"bound_Lt", t.bound.path_length_m},
                      {"bound_arrival_s", t.bound.arrival_time_s}});
  }
  return stages;
}

nlohmann::json table_json(const Options& options, const std::vector<RunStart>& starts,
                          const std::vector<Row>& rows) {
  nlohmann::json out;
  out["transitions_per_run"] = options.transitions;
  out["sampling"] = options.sampling;
  if (options.sampling == "uniform") out["sample_seed"] = options.sample_seed;
  out["runs_per_row"] = starts.size();
  out["run_phases_rad"] = nlohmann::json::array();
  for (const RunStart& s : starts)
    out["run_phases_rad"].push_back({s.g0_phase_rad, s.g1_phase_rad});
  out["rows"] = nlohmann::json::array();
  for (const Row& r : rows) {
    out["rows"].push_back({{"v", r.v},
                           {"w", r.w},
                           {"method", r.method},
                           {"Ls", cover::bench::figure_json(r.measured_Ls())},
                           {"Lt", cover::bench::figure_json(r.measured_Lt())},
                           {"ratio", cover::sim::number_or_null(r.ratio())},
                           {"eq30_law_ratio", cover::sim::number_or_null(r.eq30_law_ratio())},
                           {"bound_ratio", cover::sim::number_or_null(r.bound_ratio())},
                           {"bound_unreached", r.bound_unreached()},
                           {"transitions", r.completed()},
                           {"failures", r.requested - r.completed()},
                           {"statuses", r.statuses},
                           {"realtime_factor", r.realtime_factor()},
                           {"wall_time_s", r.wall_time_s},
                           {"per_transition", transitions_json(r)}});
  }
  if (options.plot) out["plot"] = options.plot_file;
  if (!options.transitions_plot_file.empty())
    out["transitions_plot"] = options.transitions_plot_file;
  return out;
}

int run(const std::vector<std::string>& args) {
  Options options;
  if (int rc = parse_options(args, options); rc >= 0) return rc;

  const std::vector<RunStart> starts = run_starts(options);
  std::vector<Row> rows;
  std::vector<cover::sim::TransitionTrace> first_transitions;
  for (std::size_t s = 0; s < options.settings.size(); ++s) {
    for (const std::string& method : options.methods) {
      Row row;
      row.v = options.settings[s].first;
      row.w = options.settings[s].second;
      row.method = method;
      cover::sim::TransitionTrace trace;
      if (!run_cell(options, s, starts, row, trace)) return 1;
      if (s == 0) first_transitions.push_back(std::move(trace));
      rows.push_back(std::move(row));
    }
  }
  if (!options.transitions_plot_file.empty() &&
      !cover::sim::write_transitions_plot(
          first_transitions, setting_title("one transition per method, same start", rows.front()),
          options.transitions_plot_file)) {
    std::cerr << "cannot write " << options.transitions_plot_file << "\n";
    return 1;
  }

  cover::bench::NotMeasured missing;
  for (const Row& r : rows) {
    if (r.completed() == 0) {
      char setting[64];
      std::snprintf(setting, sizeof setting, "v %.2f m/s, w %.2f rad/s, ", r.v, r.w);
      missing.add(setting + r.method + ": none of " + std::to_string(r.requested) +
                  " transitions completed, so no L_t/L_s");
    }
  }
  if (options.json) {
    std::cout << table_json(options, starts, rows).dump(2) << "\n";
  } else {
    print_table(rows);
    if (options.plot)
      std::printf("plot: %s (other methods: _<method>)\n", options.plot_file.c_str());
    if (!options.transitions_plot_file.empty())
      std::printf("transitions plot: %s\n", options.transitions_plot_file.c_str());
  }
  return missing.exit_code("table1");
}

const cover::bench::Registrar registrar{"table1", "paper Table 1: transition path ratio Lt/Ls",
                                        &run};

}  // namespace

// cover-bench scenario 1|2|3|4: the paper's real-world scenarios (sec. 5.2) in closed loop
// with the simulator: success, landing / delivery errors on the deck, final-stage tracking
// error per axis, and how much faster than real time the whole loop runs.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "cover/sim/closed_loop.hpp"
#include "cover/sim/closed_loop_report.hpp"

namespace {

// Scenario 1's UGV patterns (paper Table 3): the scenario file, the paper's L_t/L_s and its
// L_s per transition (Table 3's L_s over its eight transitions; the paper says "more than 8",
// so at most this).
struct Scenario1Pattern {
  const char* name;
  const char* file;
  double paper_ratio;
  double paper_transition_length_m;
};
constexpr Scenario1Pattern kScenario1Patterns[] = {
    {"circle", "scenario1", 1.11, 55.68 / 8.0},
    {"lines", "scenario1_lines", 1.07, 57.67 / 8.0},
    // The lines with 2 m half strokes: UGVs nearly abreast at every switch.
    {"lines-short", "scenario1_lines_short", 1.07, 57.67 / 8.0}};

const Scenario1Pattern& scenario1_pattern(const std::string& name) {
  for (const Scenario1Pattern& p : kScenario1Patterns)
    if (name == p.name) return p;
  return kScenario1Patterns[0];
}

// L_s per transition, comparable with the paper's (NaN with none).
double mean_transition_length_m(const cover::sim::ClosedLoopResult& r) {
  return r.transitions.empty()
             ? std::nan("")
             : r.total_straight_length_m / static_cast<double>(r.transitions.size());
}

double out_ratio(const cover::sim::ClosedLoopResult& r) {
  return r.total_straight_length_m > 0.0 ? r.total_path_length_m / r.total_straight_length_m
                                         : std::nan("");
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"The paper's scenarios 1-4 in closed loop (sec. 5.2)"};
  int number = 2;
  bool json = false;
  std::uint64_t seed = 0;
  std::string method = "cover";
  std::string plot_file;
  app.add_option("number", number, "scenario 1|2|3|4")->required()->check(CLI::Range(1, 4));
  app.add_flag("--json", json, "print JSON instead of a table");
  app.add_option("--seed", seed, "world seed (default: the scenario file's)");
  app.add_option("--method", method, cover::bench::joined_method_names(" | "))
      ->check(CLI::IsMember(cover::bench::method_names()));
  std::string pattern = kScenario1Patterns[0].name;
  std::vector<std::string> pattern_names;
  for (const Scenario1Pattern& p : kScenario1Patterns) pattern_names.emplace_back(p.name);
  CLI::Option* pattern_opt =
      app.add_option("--pattern", pattern,
                     "scenario 1 only: circle (default) | lines | lines-short "
                     "(2 m half strokes)")
          ->check(CLI::IsMember(pattern_names));
  CLI::Option* plot =
      app.add_option("--plot", plot_file, "write a top-view SVG (default file scenario<N>.svg)");
  plot->expected(0, 1);
  std::string scenario_file;
  app.add_option("--scenario-file", scenario_file,
                 "fly this scenario YAML instead of scenario N's (a variant of its world)");
  std::string trace_file;
  app.add_option("--trace", trace_file,
                 "write every control step (state, reference, command) as CSV to this file");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  if (pattern_opt->count() > 0 && number != 1) {
    std::cerr << "--pattern applies to scenario 1 only\n";
    return 2;
  }
  const Scenario1Pattern* scenario1 = number == 1 ? &scenario1_pattern(pattern) : nullptr;
  const std::string name = scenario1 ? scenario1->file : "scenario" + std::to_string(number);
  cover::sim::Scenario scenario = cover::sim::Scenario::load_file(
      scenario_file.empty() ? cover::sim::scenario_path(name) : scenario_file);
  if (app.count("--seed") > 0) scenario.world.seed = seed;
  const auto config = cover::uav::ControllerConfig::load_default(*cover::sampc::parse_mode(method));
  cover::sim::ClosedLoopOptions options;
  options.record_step_trace = !trace_file.empty();
  const cover::sim::ClosedLoop loop(scenario, config, options);
  const cover::sim::ClosedLoopResult result = loop.run();

  if (plot->count() > 0) {
    if (plot_file.empty()) plot_file = name + ".svg";
    const std::string title =
        "Scenario " + std::to_string(number) + ": " + scenario.description + " (" + method + ")";
    if (!cover::sim::write_path_plot(result, scenario, title, plot_file)) {
      std::cerr << "cannot write " << plot_file << "\n";
      return 1;
    }
  }
  if (!trace_file.empty() && !cover::sim::write_step_trace(result, trace_file)) {
    std::cerr << "cannot write " << trace_file << "\n";
    return 1;
  }
  if (json) {
    nlohmann::json out = cover::sim::summary_json(result);
    out["scenario"] = number;
    out["method"] = method;
    out["seed"] = scenario.world.seed;
    if (scenario1) {
      out["pattern"] = scenario1->name;
      out["paper_ratio"] = scenario1->paper_ratio;
      out["transition_length_m"] = mean_transition_length_m(result);
      out["paper_transition_length_m"] = scenario1->paper_transition_length_m;
    }
    if (plot->count() > 0) out["plot"] = plot_file;
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("Scenario %d (%s), method %s\n%s", number, scenario.description.c_str(),
                method.c_str(), cover::sim::readable_summary(result).c_str());
    if (scenario1) {
      std::printf(
          "  pattern           %s: Lt/Ls %.3f, paper (Table 3) %.2f; Ls per transition "
          "%.2f m, paper %.2f m\n",
          scenario1->name, out_ratio(result), scenario1->paper_ratio,
          mean_transition_length_m(result), scenario1->paper_transition_length_m);
    }
    if (plot->count() > 0) std::printf("  plot              %s\n", plot_file.c_str());
  }
  return result.success ? 0 : 3;
}

const cover::bench::Registrar registrar{"scenario", "paper scenarios 1-4 in closed loop", &run};

}  // namespace

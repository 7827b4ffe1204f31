// cover-bench planner: solve a fixed, seeded set of stage problems like the paper's and
// report solve time and limit violations.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "bench_registry.hpp"
#include "bench_stats.hpp"
#include "cover/config/yaml_reader.hpp"
#include "cover/planner/benchmark_problems.hpp"
#include "cover/planner/stage_planner.hpp"
#include "cover/planner/trajectory_metrics.hpp"

namespace {

using cover::bench::percentile;

// A problem fails when the planner gives no optimised trajectory, or its boundary
// conditions are off by more than 1e-6 (the limits are reported separately).
bool is_failure(const cover::planner::PlanResult& result,
                const cover::planner::TrajectoryMetrics& m) {
  constexpr double kBoundaryTolerance = 1e-6;
  return !cover::planner::is_usable(result.status) ||
         m.start_position_error_m > kBoundaryTolerance ||
         m.start_velocity_error_m_s > kBoundaryTolerance || m.start_acc_m_s2 > kBoundaryTolerance ||
         m.end_position_error_m > kBoundaryTolerance || m.end_speed_m_s > kBoundaryTolerance ||
         m.end_acc_m_s2 > kBoundaryTolerance;
}

// CPU time of this thread: unlike wall time, not inflated when other processes share the
// cores (the benchmark machine is shared), so it shows the planner's own cost.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"Stage planner: seeded paper-like problems, solve time and limit violations"};
  bool json = false;
  int count = 1000;
  unsigned seed = 2026;
  std::string config = cover::config::default_config_dir() + "/planner.yaml";
  app.add_flag("--json", json, "print JSON");
  app.add_option("--problems", count, "number of problems (>= 1)")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "problem-set seed");
  app.add_option("--config", config, "planner YAML");
  if (int rc = cover::bench::parse_args(app, args); rc >= 0) return rc;

  cover::planner::StagePlanner planner(cover::planner::PlannerParams::load_file(config));
  const auto problems = cover::planner::make_benchmark_problems(count, seed);
  std::vector<double> solve_ms, cpu_ms, speed_violation, acc_violation;
  std::vector<double> evaluations;
  int failures = 0, early_stops = 0;
  double max_speed_violation = 0.0, max_acc_violation = 0.0, total_duration_s = 0.0;
  for (const auto& problem : problems) {
    const double cpu_before = thread_cpu_ms();
    const auto result = planner.plan(problem);
    cpu_ms.push_back(thread_cpu_ms() - cpu_before);
    const auto metrics = cover::planner::measure_trajectory(result.trajectory, problem);
    solve_ms.push_back(result.solve_ms);
    evaluations.push_back(result.iterations);
    failures += is_failure(result, metrics) ? 1 : 0;
    early_stops += result.status == cover::planner::PlanStatus::EarlyStop ? 1 : 0;
    total_duration_s += metrics.duration_s;
    speed_violation.push_back(metrics.speed_violation);
    acc_violation.push_back(metrics.acc_violation);
    max_speed_violation = std::max(max_speed_violation, metrics.speed_violation);
    max_acc_violation = std::max(max_acc_violation, metrics.acc_violation);
  }

  nlohmann::json out;
  out["problems"] = count;
  out["seed"] = seed;
  out["failures"] = failures;
  out["early_stops"] = early_stops;
  out["median_ms"] = percentile(solve_ms, 0.5);
  out["p99_ms"] = percentile(solve_ms, 0.99);
  out["max_ms"] = percentile(solve_ms, 1.0);
  out["median_cpu_ms"] = percentile(cpu_ms, 0.5);
  out["p99_cpu_ms"] = percentile(cpu_ms, 0.99);
  // Mean planned stage duration: lower is more aggressive (and a looser optimum is longer).
  out["mean_duration_s"] = total_duration_s / count;
  out["median_evaluations"] = percentile(evaluations, 0.5);
  out["p99_evaluations"] = percentile(evaluations, 0.99);
  // Fractions of the limit; the speed limit is max(vm, |v0|) (see trajectory_metrics.hpp).
  out["max_speed_violation"] = max_speed_violation;
  out["p99_speed_violation"] = percentile(speed_violation, 0.99);
  out["max_acc_violation"] = max_acc_violation;
  out["p99_acc_violation"] = percentile(acc_violation, 0.99);
  if (json) {
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::printf("planner benchmark: %d problems (seed %u)\n", count, seed);
  std::printf("  %-22s %d (early stops %d)\n", "failures", failures, early_stops);
  std::printf("  %-22s median %.3f  p99 %.3f  max %.3f\n", "solve time [ms]",
              out["median_ms"].get<double>(), out["p99_ms"].get<double>(),
              out["max_ms"].get<double>());
  std::printf("  %-22s median %.3f  p99 %.3f\n", "thread CPU time [ms]",
              out["median_cpu_ms"].get<double>(), out["p99_cpu_ms"].get<double>());
  std::printf("  %-22s median %.0f  p99 %.0f\n", "cost evaluations",
              out["median_evaluations"].get<double>(), out["p99_evaluations"].get<double>());
  std::printf("  %-22s %.3f\n", "mean duration [s]", out["mean_duration_s"].get<double>());
  std::printf("  %-22s max %.4f  p99 %.4f\n", "speed violation [frac]", max_speed_violation,
              out["p99_speed_violation"].get<double>());
  std::printf("  %-22s max %.4f  p99 %.4f\n", "acc violation [frac]", max_acc_violation,
              out["p99_acc_violation"].get<double>());
  return 0;
}

const cover::bench::Registrar registrar{"planner", "stage planner: solve time and limit violations",
                                        &run};

}  // namespace

// cover-plan: plan one stage with the MINCO stage planner and print what came out.
//   cover-plan --from 5,2,1 --v0 0.5,0,0 --to 0,0,1.5 --vmax 1.0 --amax 2.0 --json
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/planner/stage_planner.hpp"
#include "cover/planner/trajectory_metrics.hpp"
#include "cover/startup/startup.hpp"

namespace {

// Parses "x,y,z" into a vector; throws CLI::ValidationError naming the flag.
Eigen::Vector3d parse_vector(const std::string& text, const std::string& flag) {
  Eigen::Vector3d v;
  std::stringstream stream(text);
  std::string item;
  int count = 0;
  while (std::getline(stream, item, ',')) {
    if (count == 3) break;
    try {
      std::size_t used = 0;
      v[count] = std::stod(item, &used);
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw CLI::ValidationError(flag, "expected x,y,z numbers, got '" + text + "'");
    }
    ++count;
  }
  if (count != 3 || std::getline(stream, item, ','))
    throw CLI::ValidationError(flag, "expected exactly three numbers x,y,z, got '" + text + "'");
  return v;
}

void write_csv(const std::string& path, const cover::planner::Trajectory& trajectory,
               double step_s) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "t,px,py,pz,vx,vy,vz,ax,ay,az\n";
  const double duration = trajectory.duration_s();
  const int steps = std::max(1, static_cast<int>(std::ceil(duration / step_s)));
  for (int k = 0; k <= steps; ++k) {
    const double t = std::min(duration, k * step_s);
    const auto p = trajectory.position(t), v = trajectory.velocity(t),
               a = trajectory.acceleration(t);
    out << t << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << v.x() << ',' << v.y() << ','
        << v.z() << ',' << a.x() << ',' << a.y() << ',' << a.z() << '\n';
  }
}

// The command line.
struct Options {
  std::string from = "0,0,0", v0 = "0,0,0", to, omega = "0,0,0", csv;
  std::string config = cover::config::default_config_dir() + "/planner.yaml";
  double vmax = 0.0, amax = 0.0, csv_step = 0.02;
  bool transition = false, json = false;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("--from", o.from, "start position x,y,z (m, stage frame)");
  app.add_option("--v0", o.v0, "start velocity x,y,z (m/s, stage frame)");
  app.add_option("--to", o.to, "goal (transition point) x,y,z (m)")->required();
  app.add_option("--vmax", o.vmax, "relative speed limit (m/s); default from the config");
  app.add_option("--amax", o.amax, "relative acceleration limit (m/s^2); default from the config");
  app.add_option("--omega", o.omega, "UGV angular velocity x,y,z (rad/s), used with --transition");
  app.add_flag("--transition", o.transition, "transition stage: v0 = v + omega x p (eq. 23)");
  app.add_option("--config", o.config, "planner YAML")->check(CLI::ExistingFile);
  app.add_option("--csv", o.csv, "write samples t,p,v,a to this file");
  app.add_option("--csv-step", o.csv_step, "CSV sample period (s)")->check(CLI::PositiveNumber);
  app.add_flag("--json", o.json, "print JSON");
}

// The stage the options describe, without its limits. Throws CLI::ValidationError for a
// malformed vector.
cover::planner::StageProblem make_problem(const Options& o) {
  cover::planner::StageProblem problem;
  problem.start_position_m = parse_vector(o.from, "--from");
  problem.start_velocity_m_s = parse_vector(o.v0, "--v0");
  problem.goal_position_m = parse_vector(o.to, "--to");
  problem.ugv_angular_velocity_rad_s = parse_vector(o.omega, "--omega");
  problem.transition_stage = o.transition;
  return problem;
}

nlohmann::json report(const cover::planner::PlanResult& result,
                      const cover::planner::TrajectoryMetrics& m) {
  nlohmann::json out;
  out["status"] = cover::planner::to_string(result.status);
  out["reason"] = result.reason;
  out["duration_s"] = m.duration_s;
  out["max_speed"] = m.max_speed_m_s;
  out["max_acc"] = m.max_acc_m_s2;
  out["speed_violation"] = m.speed_violation;
  out["acc_violation"] = m.acc_violation;
  out["end_pos_error_m"] = m.end_position_error_m;
  out["end_speed"] = m.end_speed_m_s;
  out["start_pos_error_m"] = m.start_position_error_m;
  out["start_vel_error_m_s"] = m.start_velocity_error_m_s;
  const auto& v = result.initial_velocity_m_s;
  out["initial_velocity"] = {v.x(), v.y(), v.z()};
  out["pieces"] = result.trajectory.piece_count();
  out["iterations"] = result.iterations;
  out["solve_ms"] = result.solve_ms;
  return out;
}

// Indented JSON, or one aligned "key value" line per entry.
void print_report(const nlohmann::json& out, bool json) {
  if (json) {
    std::cout << out.dump(2) << "\n";
    return;
  }
  for (const auto& [key, value] : out.items()) {
    std::cout << "  " << key << std::string(key.size() < 20 ? 20 - key.size() : 1, ' ')
              << value.dump() << "\n";
  }
}

// Plans, writes the CSV if asked, prints the report; the exit code: 0 for a usable plan,
// 3 otherwise. Throws on a bad vector, config or CSV path.
int plan_or_throw(const CLI::App& app, const Options& o) {
  // The vectors first: a malformed one is reported before a config error.
  cover::planner::StageProblem problem = make_problem(o);
  const auto params = cover::planner::PlannerParams::load_file(o.config);
  problem.vmax_m_s = app.count("--vmax") > 0 ? o.vmax : params.default_vmax_m_s;
  problem.amax_m_s2 = app.count("--amax") > 0 ? o.amax : params.default_amax_m_s2;
  cover::planner::StagePlanner planner(params);
  const auto result = planner.plan(problem);
  const auto m = cover::planner::measure_trajectory(result.trajectory, problem);
  if (!o.csv.empty()) write_csv(o.csv, result.trajectory, o.csv_step);
  print_report(report(result, m), o.json);
  return cover::planner::is_usable(result.status) ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  cover::startup::Program program;
  program.name = "cover-plan";
  program.description = "Plan one COVER stage (MINCO minimum jerk, L-BFGS) and report it";
  program.exit_codes =
      "Exit codes: 0 a usable plan; 1 an unexpected error (a CSV that cannot be written); 2 "
      "usage or configuration error (a malformed vector, a bad planner file); 3 no usable "
      "plan (the report says why).";
  program.shutdown_signals = false;  // one plan, in well under a second: Ctrl-C just ends it
  program.add_flags = [&](CLI::App& app) { add_options(app, options); };
  return cover::startup::run_main(argc, argv, program,
                                  [&](const CLI::App& app) { return plan_or_throw(app, options); });
}

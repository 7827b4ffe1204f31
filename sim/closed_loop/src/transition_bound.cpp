#include "cover/sim/transition_bound.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>

#include "cover/sim/cone_program.hpp"

namespace cover::sim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// What every arrival time shares: the start and the target's extremes over the budget.
struct BoundContext {
  const UgvMotionPattern& target;
  double start_time_s;
  Eigen::Vector2d p0;
  Eigen::Vector2d v0;
  TransitionBoundParams params;
  double acceleration_m_s2 = 0.0;           // A: the world acceleration bound
  double relative_acceleration_m_s2 = 0.0;  // |a - a_target| <= A + |a_target|max
  double speed_tolerance_m_s = 0.0;         // the arrival test on |v - v_target|, world
  double start_relative_speed_m_s = 0.0;

  Eigen::Vector2d target_position(double t_s) const {
    return target.at(start_time_s + t_s).position_m;
  }
  // The speed limit on segments starting at `t_s`: vmax, or a faster start slowing down.
  double speed_limit(double t_s) const {
    return std::max(params.vmax_m_s, start_relative_speed_m_s - relative_acceleration_m_s2 * t_s);
  }
};

BoundContext make_context(const UgvMotionPattern& target, double start_time_s,
                          const Eigen::Vector2d& p0, const Eigen::Vector2d& v0, double budget_s,
                          const TransitionBoundParams& params) {
  BoundContext context{target, start_time_s, p0, v0, params};
  // The target's extremes, sampled finely over the budget (the patterns are smooth curves
  // whose acceleration and yaw rate change over seconds, not milliseconds).
  constexpr double kSampleStep_s = 0.01;
  double acceleration_max = 0.0;
  double yaw_rate_max = 0.0;
  for (double t = 0.0; t <= budget_s + params.time_step_s; t += kSampleStep_s) {
    const UgvKinematics k = target.at(start_time_s + t);
    acceleration_max = std::max(acceleration_max, k.acceleration_m_s2.norm());
    yaw_rate_max = std::max(yaw_rate_max, std::abs(k.yaw_rate_rad_s));
  }
  context.acceleration_m_s2 = params.amax_m_s2 + acceleration_max;
  context.relative_acceleration_m_s2 = context.acceleration_m_s2 + acceleration_max;
  context.speed_tolerance_m_s =
      params.speed_threshold_m_s + yaw_rate_max * params.reach_tolerance_m;
  context.start_relative_speed_m_s = (v0 - target.at(start_time_s).velocity_m_s).norm();
  return context;
}

// The polyline's variables: p_1..p_N (x, y) then one length epigraph per segment.
struct PolylineLayout {
  int segments = 1;
  int point(int k) const { return 2 * (k - 1); }  // p_k, k >= 1 (p_0 is the start)
  int length(int k) const { return 2 * segments + k; }
  int variables() const { return 3 * segments; }
};

// Adds |sum_j w_j p_(k_j) - offset| <= rho (+ the length variable of segment `length_of`).
void add_ball(ConeProgram& program, const PolylineLayout& layout, const Eigen::Vector2d& p0,
              std::initializer_list<std::pair<int, double>> points, Eigen::Vector2d offset,
              double rho, int length_of = -1) {
  PlanarCone cone;
  for (const auto& [k, w] : points) {
    if (k == 0) {
      offset -= w * p0;
      continue;
    }
    cone.g[0].terms.emplace_back(layout.point(k), w);
    cone.g[1].terms.emplace_back(layout.point(k) + 1, w);
  }
  cone.c = offset;
  cone.rho = rho;
  if (length_of >= 0) cone.h.terms.emplace_back(layout.length(length_of), 1.0);
  program.cones.push_back(cone);
}

// The shortest polyline arriving at T (the header's convex problem).
ConeProgram arrival_program(const BoundContext& c, double arrival_s, PolylineLayout& layout) {
  layout.segments = std::max(1, static_cast<int>(std::lround(arrival_s / c.params.time_step_s)));
  const int n = layout.segments;
  const double dt = arrival_s / n;
  const double a = c.acceleration_m_s2;
  ConeProgram program;
  program.variables = layout.variables();
  program.cost = Eigen::VectorXd::Zero(program.variables);
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  for (int k = 0; k < n; ++k) {
    program.cost(layout.length(k)) = 1.0;
    add_ball(program, layout, c.p0, {{k + 1, 1.0}, {k, -1.0}}, zero, 0.0, k);
    const Eigen::Vector2d target_step = c.target_position((k + 1) * dt) - c.target_position(k * dt);
    add_ball(program, layout, c.p0, {{k + 1, 1.0}, {k, -1.0}}, target_step,
             dt * c.speed_limit(k * dt));
    if (k == 0) {
      add_ball(program, layout, c.p0, {{1, 1.0}, {0, -1.0}}, c.v0 * dt, 0.5 * a * dt * dt);
    } else {
      add_ball(program, layout, c.p0, {{k + 1, 1.0}, {k, -2.0}, {k - 1, 1.0}}, zero, a * dt * dt);
    }
  }
  const UgvKinematics end = c.target.at(c.start_time_s + arrival_s);
  add_ball(program, layout, c.p0, {{n, 1.0}}, end.position_m, c.params.reach_tolerance_m);
  add_ball(program, layout, c.p0, {{n, 1.0}, {n - 1, -1.0}}, end.velocity_m_s * dt,
           (c.speed_tolerance_m_s + 0.5 * a * dt) * dt);
  return program;
}

struct ArrivalSolution {
  double length_m = kInfinity;  // certified lower bound; +inf if infeasible
  std::vector<Eigen::Vector2d> path_m;
};

ArrivalSolution solve_arrival(const BoundContext& c, double arrival_s, int& solves) {
  ArrivalSolution solution;
  // Necessary: the relative distance can shrink by at most the speed limit's integral.
  double closable_m = 0.0;
  for (double t = 0.0; t < arrival_s; t += c.params.time_step_s)
    closable_m += c.speed_limit(t) * std::min(c.params.time_step_s, arrival_s - t);
  const double distance_m = (c.p0 - c.target_position(0.0)).norm();
  if (distance_m - closable_m > c.params.reach_tolerance_m) return solution;

  PolylineLayout layout;
  const ConeProgram program = arrival_program(c, arrival_s, layout);
  // Start: the straight line to where the target will be.
  Eigen::VectorXd start(program.variables);
  const Eigen::Vector2d goal = c.target_position(arrival_s);
  for (int k = 1; k <= layout.segments; ++k)
    start.segment<2>(layout.point(k)) = c.p0 + (goal - c.p0) * k / layout.segments;
  for (int k = 0; k < layout.segments; ++k) start(layout.length(k)) = (goal - c.p0).norm() + 1.0;
  ConeProgramSettings settings;
  settings.gap_tolerance = c.params.gap_tolerance_m;
  ++solves;
  const ConeProgramResult result = solve_cone_program(program, start, settings);
  if (!result.feasible) return solution;
  solution.length_m = std::max(0.0, result.lower_bound);
  solution.path_m.push_back(c.p0);
  for (int k = 1; k <= layout.segments; ++k)
    solution.path_m.emplace_back(result.z.segment<2>(layout.point(k)));
  return solution;
}

}  // namespace

TransitionBoundResult shortest_transition_bound(const UgvMotionPattern& target, double start_time_s,
                                                const Eigen::Vector2d& start_position_m,
                                                const Eigen::Vector2d& start_velocity_m_s,
                                                double budget_s,
                                                const TransitionBoundParams& params) {
  TransitionBoundResult result;
  if (!(budget_s > 0.0) || !start_position_m.allFinite() || !start_velocity_m_s.allFinite()) {
    return result;
  }
  const BoundContext context =
      make_context(target, start_time_s, start_position_m, start_velocity_m_s, budget_s, params);
  double best_time_s = 0.0;
  ArrivalSolution best;
  const auto consider = [&](double arrival_s) {
    ArrivalSolution s = solve_arrival(context, arrival_s, result.solves);
    if (s.length_m < best.length_m) {
      best = std::move(s);
      best_time_s = arrival_s;
    }
    return s.length_m;
  };
  // The coarse grid, ending on the budget.
  const int coarse =
      std::max(1, static_cast<int>(std::ceil(budget_s / params.coarse_arrival_step_s)));
  for (int j = 1; j <= coarse; ++j) consider(std::min(budget_s, j * params.coarse_arrival_step_s));
  if (!std::isfinite(best.length_m)) return result;

  // Golden-section refinement on the bracket around the best grid point.
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = std::max(1e-3, best_time_s - params.coarse_arrival_step_s);
  double hi = std::min(budget_s, best_time_s + params.coarse_arrival_step_s);
  double x1 = hi - golden * (hi - lo);
  double x2 = lo + golden * (hi - lo);
  double f1 = consider(x1);
  double f2 = consider(x2);
  while (hi - lo > params.arrival_resolution_s) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - golden * (hi - lo);
      f1 = consider(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + golden * (hi - lo);
      f2 = consider(x2);
    }
  }
  result.reached = true;
  result.arrival_time_s = best_time_s;
  result.path_length_m = best.length_m;
  result.straight_length_m = (best.path_m.back() - start_position_m).norm();
  result.path_m = std::move(best.path_m);
  return result;
}

}  // namespace cover::sim

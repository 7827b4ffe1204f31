#include "cover/sim/cone_program.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace cover::sim {
namespace {

// A cone touches a few neighbouring variables; fixed-capacity local blocks keep the Newton
// steps free of allocations.
constexpr int kMaxLocal = 10;
using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLocal, 1>;
using LocalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxLocal, kMaxLocal>;

// One cone on its own variables: G (2 x L) and h (L) dense over `index`.
struct LocalCone {
  std::vector<int> index;
  Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, kMaxLocal> g;
  LocalVector h;
  Eigen::Vector2d c;
  double rho = 0.0;
  std::vector<int> hessian_slot;  // where local (i, j) sits in the sparse Hessian's values
};

int local_slot(std::vector<int>& index, int variable) {
  const auto found = std::find(index.begin(), index.end(), variable);
  if (found != index.end()) return static_cast<int>(found - index.begin());
  if (index.size() >= static_cast<std::size_t>(kMaxLocal)) {
    throw std::invalid_argument("cone program: a cone touches more than 10 variables");
  }
  index.push_back(variable);
  return static_cast<int>(index.size()) - 1;
}

LocalCone localise(const PlanarCone& cone, int slack_variable) {
  LocalCone local;
  for (const SparseRow& row : cone.g)
    for (const auto& [v, a] : row.terms) local_slot(local.index, v);
  for (const auto& [v, a] : cone.h.terms) local_slot(local.index, v);
  if (slack_variable >= 0) local_slot(local.index, slack_variable);
  const auto size = static_cast<Eigen::Index>(local.index.size());
  local.g.setZero(2, size);
  local.h.setZero(size);
  for (int r = 0; r < 2; ++r)
    for (const auto& [v, a] : cone.g[r].terms) local.g(r, local_slot(local.index, v)) += a;
  for (const auto& [v, a] : cone.h.terms) local.h(local_slot(local.index, v)) += a;
  if (slack_variable >= 0) local.h(local_slot(local.index, slack_variable)) += 1.0;
  local.c = cone.c;
  local.rho = cone.rho;
  return local;
}

// The barrier problem t cost^T z - sum log((rho + h z)^2 - |G z - c|^2), by Newton steps.
// The Hessian's sparsity is fixed, so it is laid out and analysed once.
class Barrier {
 public:
  Barrier(std::vector<LocalCone> cones, Eigen::VectorXd cost)
      : cones_(std::move(cones)), cost_(std::move(cost)) {
    const auto n = static_cast<Eigen::Index>(cost_.size());
    std::vector<Eigen::Triplet<double>> pattern;
    for (const LocalCone& cone : cones_)
      for (const int i : cone.index)
        for (const int j : cone.index) pattern.emplace_back(i, j, 1.0);
    // A variable no cone bounds would make the Hessian singular; a tiny ridge keeps the
    // factorisation defined without moving the step measurably.
    for (Eigen::Index i = 0; i < n; ++i) pattern.emplace_back(i, i, 1.0);
    hessian_.resize(n, n);
    hessian_.setFromTriplets(pattern.begin(), pattern.end());
    hessian_.makeCompressed();
    for (LocalCone& cone : cones_) {
      for (const int i : cone.index)
        for (const int j : cone.index) cone.hessian_slot.push_back(value_slot(i, j));
    }
    for (Eigen::Index i = 0; i < n; ++i) diagonal_slot_.push_back(value_slot(i, i));
    solver_.analyzePattern(hessian_);
  }

  // +inf outside the cones' interiors.
  double value(const Eigen::VectorXd& z, double t) const {
    double total = t * cost_.dot(z);
    for (const LocalCone& cone : cones_) {
      const LocalVector x = gather(cone, z);
      const double g = cone.rho + cone.h.dot(x);
      const double q = g * g - (cone.g * x - cone.c).squaredNorm();
      if (!(g > 0.0) || !(q > 0.0)) return std::numeric_limits<double>::infinity();
      total -= std::log(q);
    }
    return total;
  }

  // The Newton step at z (feasible); false if the system cannot be solved.
  bool newton_step(const Eigen::VectorXd& z, double t, Eigen::VectorXd& step,
                   double& decrement_squared) {
    Eigen::VectorXd gradient = t * cost_;
    double* values = hessian_.valuePtr();
    std::fill(values, values + hessian_.nonZeros(), 0.0);
    for (const int slot : diagonal_slot_) values[slot] = 1e-12;
    for (const LocalCone& cone : cones_) {
      const LocalVector x = gather(cone, z);
      const double g = cone.rho + cone.h.dot(x);
      const Eigen::Vector2d e = cone.g * x - cone.c;
      const double q = g * g - e.squaredNorm();
      const LocalVector dq = 2.0 * g * cone.h - 2.0 * cone.g.transpose() * e;
      const LocalMatrix hessian =
          dq * dq.transpose() / (q * q) -
          (2.0 * cone.h * cone.h.transpose() - 2.0 * cone.g.transpose() * cone.g) / q;
      const auto size = static_cast<Eigen::Index>(cone.index.size());
      std::size_t slot = 0;
      for (Eigen::Index i = 0; i < size; ++i) {
        gradient(cone.index[static_cast<std::size_t>(i)]) -= dq(i) / q;
        for (Eigen::Index j = 0; j < size; ++j) values[cone.hessian_slot[slot++]] += hessian(i, j);
      }
    }
    solver_.factorize(hessian_);
    if (solver_.info() != Eigen::Success) return false;
    step = solver_.solve(-gradient);
    if (solver_.info() != Eigen::Success || !step.allFinite()) return false;
    decrement_squared = -gradient.dot(step);
    return true;
  }

 private:
  int value_slot(Eigen::Index row, Eigen::Index col) const {
    const int* inner = hessian_.innerIndexPtr();
    const int* outer = hessian_.outerIndexPtr();
    const int* found =
        std::lower_bound(inner + outer[col], inner + outer[col + 1], static_cast<int>(row));
    return static_cast<int>(found - inner);
  }

  static LocalVector gather(const LocalCone& cone, const Eigen::VectorXd& z) {
    LocalVector x(static_cast<Eigen::Index>(cone.index.size()));
    for (std::size_t i = 0; i < cone.index.size(); ++i)
      x(static_cast<Eigen::Index>(i)) = z(cone.index[i]);
    return x;
  }

  std::vector<LocalCone> cones_;
  Eigen::VectorXd cost_;
  Eigen::SparseMatrix<double> hessian_;
  std::vector<int> diagonal_slot_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

// Centres z at barrier weight t (Newton with backtracking line search). `stop` ends it
// early (phase I: the slack went negative). Returns false if a step failed.
template <typename Stop>
bool centre(Barrier& barrier, Eigen::VectorXd& z, double t, int& steps, int max_steps, Stop stop) {
  constexpr double kArmijo = 0.25;
  // Centred when the Newton decrement says the barrier is within 1e-9 of its minimum; a
  // centring that needs more than kMaxCentringSteps is as close as round-off lets it get.
  constexpr double kCentredDecrementSquared = 2e-9;
  constexpr int kMaxCentringSteps = 60;
  Eigen::VectorXd step;
  double decrement_squared = 0.0;
  for (int local = 0; local < kMaxCentringSteps && steps < max_steps; ++local) {
    if (!barrier.newton_step(z, t, step, decrement_squared)) return false;
    ++steps;
    if (decrement_squared < kCentredDecrementSquared) return true;
    const double f = barrier.value(z, t);
    double s = 1.0;
    Eigen::VectorXd next = z + step;
    double f_next = barrier.value(next, t);
    while (!(f_next <= f - kArmijo * s * decrement_squared) && s > 1e-9) {
      s *= 0.5;
      next = z + s * step;
      f_next = barrier.value(next, t);
    }
    if (s <= 1e-9) return true;  // no progress possible at this precision: centred enough
    z = next;
    if (stop(z)) return true;
  }
  return true;
}

constexpr double kBarrierGrowth = 20.0;
// Phase I minimises slack + cost / kSlackPenalty: an exact penalty while the cones'
// multipliers stay below it.
constexpr double kSlackPenalty = 1e4;

}  // namespace

double SparseRow::dot(const Eigen::VectorXd& z) const {
  double total = 0.0;
  for (const auto& [v, a] : terms) total += a * z(v);
  return total;
}

ConeProgramResult solve_cone_program(const ConeProgram& program, const Eigen::VectorXd& start,
                                     const ConeProgramSettings& settings) {
  ConeProgramResult result;
  const int n = program.variables;
  const double barrier_parameter = 2.0 * static_cast<double>(program.cones.size());

  // Phase I: minimise the slack s added to every cone's radius, from `start`.
  std::vector<LocalCone> slack_cones;
  double worst = 0.0;
  for (const PlanarCone& cone : program.cones) {
    slack_cones.push_back(localise(cone, n));
    double g = cone.rho + cone.h.dot(start);
    const Eigen::Vector2d e(cone.g[0].dot(start) - cone.c.x(), cone.g[1].dot(start) - cone.c.y());
    worst = std::max(worst, e.norm() - g);
  }
  Eigen::VectorXd z(n + 1);
  z.head(n) = start;
  z(n) = worst + 1.0;
  // The cost, lightly weighted, keeps variables that only an epigraph bounds (a length
  // above a norm) from running off while the slack shrinks.
  Eigen::VectorXd slack_cost(n + 1);
  slack_cost.head(n) = program.cost / kSlackPenalty;
  slack_cost(n) = 1.0;
  Barrier phase_one(std::move(slack_cones), slack_cost);
  const auto negative_slack = [n](const Eigen::VectorXd& x) { return x(n) < 0.0; };
  for (double t = barrier_parameter / (z(n) + 1.0);; t *= kBarrierGrowth) {
    if (!centre(phase_one, z, t, result.newton_steps, settings.max_newton_steps, negative_slack)) {
      return result;
    }
    if (negative_slack(z)) break;
    // Centred so closely that the slack cannot fall below zero any more: infeasible.
    if (barrier_parameter / t < settings.gap_tolerance * 1e-3 ||
        result.newton_steps >= settings.max_newton_steps) {
      return result;
    }
  }

  // Phase II: the central path from the strictly feasible point.
  std::vector<LocalCone> cones;
  for (const PlanarCone& cone : program.cones) cones.push_back(localise(cone, -1));
  Eigen::VectorXd x = z.head(n);
  Barrier barrier(std::move(cones), program.cost);
  const auto never = [](const Eigen::VectorXd&) { return false; };
  double t = barrier_parameter / std::max(1.0, std::abs(program.cost.dot(x)));
  while (true) {
    if (!centre(barrier, x, t, result.newton_steps, settings.max_newton_steps, never)) break;
    if (barrier_parameter / t < settings.gap_tolerance ||
        result.newton_steps >= settings.max_newton_steps) {
      break;
    }
    t *= kBarrierGrowth;
  }
  result.feasible = true;
  result.z = x;
  result.value = program.cost.dot(x);
  result.lower_bound = result.value - barrier_parameter / t;
  return result;
}

}  // namespace cover::sim

#pragma once

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

namespace cover::sim {

// A small second-order cone program in the plane:
//
//   minimise cost^T z   subject to   |G_i z - c_i| <= rho_i + h_i^T z   for every cone i,
//
// where each G_i has two rows. Every row is sparse (a list of (variable, coefficient)), so a
// problem whose cones each touch a few neighbouring variables (a trajectory on a time grid)
// has a banded Hessian and one Newton step costs O(variables).
struct SparseRow {
  std::vector<std::pair<int, double>> terms;
  double dot(const Eigen::VectorXd& z) const;
};

struct PlanarCone {
  std::array<SparseRow, 2> g;
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  SparseRow h;
  double rho = 0.0;
};

struct ConeProgram {
  int variables = 0;
  Eigen::VectorXd cost;
  std::vector<PlanarCone> cones;
};

struct ConeProgramSettings {
  // Stops when the duality gap 2 m / t of the barrier (m cones, each a barrier of
  // parameter 2) is below this, in the cost's units.
  double gap_tolerance = 1e-4;
  int max_newton_steps = 1000;  // over both phases
};

struct ConeProgramResult {
  bool feasible = false;     // a strictly feasible point was found
  double value = 0.0;        // cost^T z at the returned z
  double lower_bound = 0.0;  // value - duality gap: no feasible z costs less
  Eigen::VectorXd z;
  int newton_steps = 0;
};

// Primal log-barrier method (Boyd & Vandenberghe ch. 11): a phase I that minimises a common
// slack on every cone from `start` (any point) to find a strictly feasible point, then the
// central path to the optimum, each centring by Newton steps on a sparse LDLT. A convex
// problem, so the optimum is global; `lower_bound` is certified by the gap.
ConeProgramResult solve_cone_program(const ConeProgram& program, const Eigen::VectorXd& start,
                                     const ConeProgramSettings& settings = {});

}  // namespace cover::sim
